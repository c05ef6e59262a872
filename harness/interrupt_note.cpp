#include "harness/interrupt_note.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <sstream>

namespace rtbench {
namespace {

// Two buffers: the note is written into the one not being shown, then shown by one atomic store,
// so a signal never reads a note half written.
constexpr std::size_t kNoteBytes = 4096;
char notes[2][kNoteBytes];
std::atomic<int> shown{-1};

void writeNoteAndDie(int signal) {
    const int which = shown.load();
    if (which >= 0) {
        const char* text = notes[which];
        std::size_t left = std::strlen(text);
        while (left > 0) {
            const ssize_t n = write(STDERR_FILENO, text, left);
            if (n <= 0) break;
            text += n;
            left -= std::size_t(n);
        }
    }
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

}  // namespace

void setInterruptNote(const std::string& note) {
    static const bool installed = [] {
        for (int s : {SIGINT, SIGTERM, SIGHUP}) std::signal(s, writeNoteAndDie);
        return true;
    }();
    (void)installed;
    if (note.empty()) {
        shown.store(-1);
        return;
    }
    const int next = shown.load() == 0 ? 1 : 0;
    const std::size_t n = std::min(note.size(), kNoteBytes - 1);
    std::memcpy(notes[next], note.data(), n);
    notes[next][n] = '\0';
    shown.store(next);
}

std::string interruptNote(int kept, int planned, const std::string& runsCsv, const std::string& commandLine) {
    std::istringstream words(commandLine);
    std::string word, resume;
    while (words >> word)
        if (word != "--force" && word != "-f") resume += (resume.empty() ? "" : " ") + word;
    std::ostringstream out;
    out << "\nrtbench: interrupted: " << kept << " of " << planned << " run(s) have their rows in " << runsCsv
        << " and are kept; the run in progress is lost. To resume (the kept runs are not run again):\n  " << resume
        << "\n";
    return out.str();
}

}  // namespace rtbench
