#pragma once
// Progress on stderr, the same for every command: on a terminal one status line that rewrites
// itself in place (a line per running job, joined), and a permanent line only when something
// finishes; in a log (stderr not a terminal) only the permanent lines; with --quiet nothing.
// Results and errors are not progress: they print whatever the mode.
//
// Thread-safe: campaign workers (core/campaign.h) update their own parts of the status line.
#include <string>

#include "core/input_error.h"

namespace chutelab::progress {

enum class Mode { terminal, log, quiet };

Mode mode();
void set_quiet(bool quiet);  // --quiet
bool quiet();

// How a line shows a mention of an input (core/input_error.h: mention("dem.ladder")): the command
// line's flag, Python's keyword. The key itself until a front end sets it (once, before any thread).
void set_mention_names(FieldNames names);

// A permanent line (the status line is cleared first and drawn again below it), mentions shown by
// the front end's names.
void line(const std::string& text);

// This thread's part of the status line (terminal only); empty text removes it.
void status(const std::string& text);
// Text shown before the parts, e.g. "DEM runs 3/32"; empty removes it.
void status_prefix(const std::string& text);
// Removes the status line from the screen (before results are printed to stdout).
void clear();

// Set by a campaign around each job it runs: a job's own end-of-run line is then left to the
// campaign, which prints one line per job.
bool in_campaign_job();
class CampaignJobScope {
 public:
  CampaignJobScope();
  ~CampaignJobScope();
  CampaignJobScope(const CampaignJobScope&) = delete;
  CampaignJobScope& operator=(const CampaignJobScope&) = delete;

 private:
  bool was_;
};

}  // namespace chutelab::progress
