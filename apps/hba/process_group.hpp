#pragma once
// The processes this run is one of: mpirun's ranks when hba was built with
// MPI (HBA_WITH_MPI) and started by a launcher, else this process alone.
// MPI starts only under a launcher: a plain `hba` call pays nothing for it.
#include "hba/dist/group.hpp"

namespace hba::cli {

// Call once, first thing in main. Throws hba::Error if MPI cannot start.
const dist::Group& startProcessGroup(int& argc, char**& argv);
// The group started by startProcessGroup (one process before it).
const dist::Group& processGroup();
// Ends the run with `code`: in a group of several, every member ends (MPI
// aborts the job: a failed member never leaves the others waiting);
// otherwise MPI, if started, is finished and `code` returned.
int endProcessGroup(int code);

}  // namespace hba::cli
