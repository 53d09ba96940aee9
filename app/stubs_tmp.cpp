#include "app/commands.h"
namespace chutelab::app {
void add_validate(CLI::App&, Action&) {}
void add_diagnose(CLI::App&, Action&) {}
void add_synthesize(CLI::App&, Action&) {}
}
