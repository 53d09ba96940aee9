#pragma once
// How many cores a new piece of work may take without slowing someone else's: the cores minus what
// the machine's other processes keep busy now. The 1-minute load average answered this before and
// counted chutelab's own finished runs as someone else's work (an idle 2-core machine then got one
// job of one thread for minutes after a previous command), so the busy time is sampled now.
#include <chrono>

namespace chutelab {

// Cores kept busy by other processes over a short window (0 when it cannot be read). Our own
// process's CPU time in the window is left out; so is the time of niced processes, which give way
// to ours.
double busy_cores_of_others(std::chrono::milliseconds window = std::chrono::milliseconds(100));

// The hardware's cores minus busy_cores_of_others(), rounded, at least 1.
int free_cores();

}  // namespace chutelab
