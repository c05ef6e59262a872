// `rtbench unpack ARCHIVE DIR`: a GPU campaign's archive (scripts/gpu_campaign.sh run) comes back
// from a borrowed machine, so nothing in it is trusted. Allowed: folders of one plain name (a
// config's results folder) and regular files in them, CONFIG/FILE, of plain names (letters,
// digits, '.', '_', '-', not starting with '.'), with no setuid, setgid,
// sticky or world-writable bit. Refused, naming the first such entry: absolute or '..'
// paths, deeper paths, links (symbolic or hard), devices, FIFOs, sockets, sparse files, a name
// twice, a file over the per-file cap or an archive over the total cap (counted in the bytes read,
// not the headers' sizes), over 100,000 entries or 1,000 config folders, a truncated or unreadable
// archive. Paths in errors have their control characters escaped.
// The whole archive is read and checked before anything is written; then every file goes to a
// temporary name (O_EXCL | O_NOFOLLOW, relative to the held folders) and only when all are written
// are they renamed into place: a refused or failed unpack leaves no file of it in DIR.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rtbench {

struct UnpackLimits {
    std::uint64_t fileBytes = 512ull << 20;   // one runs.csv, samples.csv or hit-record file
    std::uint64_t totalBytes = 2ull << 30;    // the archive unpacked
    // Entries and config folders: a campaign has a folder per config of record, a few files in each.
    std::size_t entries = 100000;
    std::size_t folders = 1000;
};

// Unpacks `archive` (tar, optionally gzip or xz) into `dir` (made 0755 if absent; never a link)
// and returns the files written as CONFIG/FILE, in the archive's order. Files are written 0644
// and folders made 0755 whatever the archive says. Throws rtbench::Error naming the archive and
// the refused entry, or the file that could not be written.
std::vector<std::string> unpackCampaign(const std::string& archive, const std::string& dir, const UnpackLimits& limits = {});

}  // namespace rtbench
