#include "input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "error.h"
#include "text.h"

namespace rtbench {

std::uint64_t fnv1a64(std::string_view bytes) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    return h;
}

std::string hex64(std::uint64_t value) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(value));
    return buf;
}

namespace {

std::string limitText(std::uint64_t bytes) {
    if (bytes >= (1ull << 30) && bytes % (1ull << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
    if (bytes >= (1ull << 20) && bytes % (1ull << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

std::string kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

// Closes the descriptor however the read ends.
struct Fd {
    int fd;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

std::string readInputFile(const std::string& path, std::uint64_t maxBytes, const std::string& what) {
    const std::string name = printable(path);
    const Fd file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
    if (file.fd < 0) {
        const int why = errno;
        if (why == ENOENT) throw Error(name + ": " + what + " not found");
        if (why == ELOOP) throw Error(name + ": " + what + " is a symlink loop (too many levels of symbolic links)");
        throw Error(name + ": cannot open the " + what + ": " + std::strerror(why));
    }
    struct stat st{};
    if (::fstat(file.fd, &st) != 0) throw Error(name + ": cannot stat the " + what + ": " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw Error(name + ": the " + what + " is " + kindOf(st.st_mode) + ", not a regular file");
    if (std::uint64_t(st.st_size) > maxBytes)
        throw Error(name + ": the " + what + " is " + std::to_string(st.st_size) + " bytes, over the limit of " +
                    limitText(maxBytes));
    // Read what fstat says is there, then on to the end (the file may grow while read; a
    // procfs-like file says 0), never past the limit.
    std::string bytes(std::size_t(st.st_size), '\0');
    std::size_t done = 0;
    char chunk[65536];
    while (true) {
        const bool intoBuffer = done < bytes.size();
        const ssize_t n = intoBuffer ? ::read(file.fd, bytes.data() + done, bytes.size() - done)
                                     : ::read(file.fd, chunk, sizeof chunk);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw Error(name + ": read error in the " + what + ": " + std::strerror(errno));
        }
        if (n == 0) break;
        if (!intoBuffer) {
            if (done + std::size_t(n) > maxBytes)
                throw Error(name + ": the " + what + " grew over the limit of " + limitText(maxBytes) + " while read");
            bytes.append(chunk, std::size_t(n));
        }
        done += std::size_t(n);
    }
    bytes.resize(done);
    return bytes;
}

InputFile fingerprint(const std::string& path, std::string_view bytes) {
    return {path, bytes.size(), hex64(fnv1a64(bytes))};
}

std::string inputsHash(const std::vector<InputFile>& inputs) {
    std::string all;
    for (const InputFile& f : inputs) all += f.hash + ":" + std::to_string(f.bytes) + ";";
    return hex64(fnv1a64(all));
}

}  // namespace rtbench
