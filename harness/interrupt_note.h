// What a sweep says when it is interrupted (Ctrl-C, SIGTERM, SIGHUP): the rows it kept, where, and
// the command that resumes it. The note is formatted while the sweep runs; the handler only writes
// it (write(2) is async-signal-safe), then dies of the same signal, so the exit status still says
// which one. Rows already appended stand: a resume keeps them (docs/results-folder.md).
#pragma once
#include <string>

namespace rtbench {

// Installs the handlers (once) and makes `note` the text they write; an empty note writes nothing.
void setInterruptNote(const std::string& note);

// The note for a sweep whose `kept` of `planned` runs have rows in `runsCsv`, run by `commandLine`
// (its --force/-f left out of the command that resumes, which would re-run the kept rows).
std::string interruptNote(int kept, int planned, const std::string& runsCsv, const std::string& commandLine);

}  // namespace rtbench
