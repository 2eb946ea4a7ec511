#pragma once
// How the tool shows progress (hba::Progress): a bar with rate and ETA,
// redrawn in place, when stderr is a terminal; a plain line every 10 s
// (HBA_PROGRESS_SECONDS) otherwise (logs, CI, pipes). Periodic lines also
// reach --log-file.
namespace hba::cli {

// `show_bar`: draw the bar (stderr is a terminal and messages are not quiet).
void installProgressDisplay(bool show_bar);

}  // namespace hba::cli
