#pragma once
// The temporary paths of a run (OutputFolder's staging folders, a DEM cache entry being written),
// removed when a signal ends the process, and the thread that removes them. core/output_folder.h
// includes this header: its users need no other.
#include <filesystem>
#include <mutex>

namespace chutelab {

// Temporary paths removed when a signal ends the process (install_interrupt_cleanup()).
void register_temporary(const std::filesystem::path& p);
void unregister_temporary(const std::filesystem::path& p);
// Catches every signal that would end the process and can be caught (SIGHUP, SIGINT, SIGQUIT,
// SIGTERM, SIGALRM, SIGXCPU, SIGPIPE, ...; call before any thread starts) and handles it on a thread
// of its own: removes the registered temporaries, says so on stderr, exits 128 + the signal's number
// (130 for SIGINT, 143 for SIGTERM). SIGKILL's leftovers are swept by the next run
// (sweep_dead_staging(), core/output_folder.h).
void install_interrupt_cleanup();
// The command has said in its one line why it ends: a signal from now on still removes the
// temporaries and exits, but adds no second line. (Under mpirun, the launcher kills the ranks still
// finishing once one rank has exited with the same error.)
void quiet_interrupts();
// Held while a run places its outputs (OutputFolder::commit()): a signal's cleanup waits for it, so
// that --out is whole again before the process ends.
std::mutex& temporaries_mutex();

}  // namespace chutelab
