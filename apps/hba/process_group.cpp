// Without MPI: this process alone.
#include "process_group.hpp"

namespace hba::cli {

const dist::Group& startProcessGroup(int&, char**&) { return dist::singleProcess(); }
const dist::Group& processGroup() { return dist::singleProcess(); }
int endProcessGroup(int code) { return code; }

}  // namespace hba::cli
