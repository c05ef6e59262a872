// rtbench unpack (harness/unpack.h) on archives built here with libarchive's writer: a campaign's
// archive unpacks whole, byte for byte, 0644 and 0755; each hostile entry (links, devices, a FIFO,
// setuid and world-writable modes, '..', absolute and deep paths, a name twice, a lying header, a
// truncated archive, the caps) is refused by name and leaves nothing in the folder, nor does a
// folder that is a link.
#include <archive.h>
#include <archive_entry.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "harness/unpack.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

// One entry to write: a path, its type and mode, its bytes (and, for links, a target).
struct Member {
    std::string path;
    std::string data;
    mode_t type = AE_IFREG;
    mode_t mode = 0644;
    std::string link;           // symbolic or hard link target
    bool hardlink = false;
};

Member file(const std::string& path, const std::string& data = "run,status\n000,ok\n") { return {path, data}; }
Member folder(const std::string& path) { return {path, "", AE_IFDIR, 0755}; }

// A tar archive (xz-compressed unless `plain`) of `members` at `path`.
void writeArchive(const std::string& path, const std::vector<Member>& members, bool plain = false) {
    archive* a = archive_write_new();
    archive_write_set_format_pax_restricted(a);
    if (!plain) archive_write_add_filter_xz(a);
    ASSERT_EQ(archive_write_open_filename(a, path.c_str()), ARCHIVE_OK) << archive_error_string(a);
    for (const Member& m : members) {
        archive_entry* e = archive_entry_new();
        archive_entry_set_pathname(e, m.path.c_str());
        archive_entry_set_filetype(e, m.type);
        archive_entry_set_perm(e, m.mode);
        if (m.hardlink) archive_entry_set_hardlink(e, m.link.c_str());
        else if (!m.link.empty()) archive_entry_set_symlink(e, m.link.c_str());
        archive_entry_set_size(e, la_int64_t(m.data.size()));
        if (m.type == AE_IFCHR || m.type == AE_IFBLK) archive_entry_set_rdev(e, makedev(1, 3));
        archive_write_header(a, e);
        if (!m.data.empty()) archive_write_data(a, m.data.data(), m.data.size());
        archive_entry_free(e);
    }
    archive_write_close(a);
    archive_write_free(a);
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

class Unpack : public ::testing::Test {
protected:
    // Unpacks `members` into a fresh folder; the error's text, or "" when it unpacked.
    std::string refusal(const std::vector<Member>& members, const UnpackLimits& limits = {}) {
        writeArchive(archive_, members);
        try {
            unpackCampaign(archive_, out_, limits);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
    // Nothing but the folders that were there before: no file, no temporary.
    std::size_t filesIn(const std::string& dir) const {
        std::size_t n = 0;
        for (const auto& entry : fs::recursive_directory_iterator(dir)) n += !entry.is_directory();
        return n;
    }
    TempDir dir_;
    std::string archive_ = dir_.file("campaign.tar.xz"), out_ = dir_.file("out");
};

TEST_F(Unpack, ACampaignUnpacksWholeWithItsOwnModes) {
    const std::string samples(200000, 'x');
    writeArchive(archive_, {folder("./"), folder("./bunny"), file("./bunny/runs.csv"), {"./bunny/samples.csv", samples, AE_IFREG, 0664},
                            folder("./strategies"), file("./strategies/context.json", "{}\n")});
    const std::vector<std::string> files = unpackCampaign(archive_, out_);
    EXPECT_EQ(files, (std::vector<std::string>{"bunny/runs.csv", "bunny/samples.csv", "strategies/context.json"}));
    EXPECT_EQ(slurp(out_ + "/bunny/runs.csv"), "run,status\n000,ok\n");
    EXPECT_EQ(slurp(out_ + "/bunny/samples.csv"), samples);
    EXPECT_EQ(slurp(out_ + "/strategies/context.json"), "{}\n");
    EXPECT_EQ(fs::status(out_ + "/bunny/samples.csv").permissions(), fs::perms(0644)) << "ours, not the archive's 0664 (umask 002)";
    EXPECT_EQ(fs::status(out_ + "/bunny").permissions(), fs::perms(0755));
    EXPECT_EQ(filesIn(out_), 3u) << "no temporary left";
    // Unpacked again over itself: the same files, replaced whole.
    EXPECT_EQ(unpackCampaign(archive_, out_).size(), 3u);
    EXPECT_EQ(filesIn(out_), 3u);
}

TEST_F(Unpack, EachHostileEntryIsRefusedByNameAndNothingIsWritten) {
    const std::vector<std::pair<Member, std::string>> cases = {
        {{"bunny/evil", "", AE_IFLNK, 0777, "/etc/passwd"}, "'bunny/evil': a symbolic link"},
        {{"bunny/hard", "", AE_IFREG, 0644, "bunny/runs.csv", true}, "'bunny/hard': a hard link"},
        {{"bunny/null", "", AE_IFCHR, 0644}, "'bunny/null': a character device"},
        {{"bunny/disk", "", AE_IFBLK, 0644}, "'bunny/disk': a block device"},
        {{"bunny/pipe", "", AE_IFIFO, 0644}, "'bunny/pipe': a FIFO"},
        {{"bunny/suid", "x", AE_IFREG, 04755}, "'bunny/suid': mode 4755: setuid"},
        {{"bunny/sgid", "x", AE_IFREG, 02755}, "'bunny/sgid': mode 2755"},
        {{"bunny/open", "x", AE_IFREG, 0666}, "'bunny/open': mode 0666: setuid, setgid, sticky or world-writable"},
        {{"bunny/\x1b[2Jx", "x"}, "'bunny/\\x1B[2Jx': '\\x1B[2Jx' is not a plain name"},  // escaped, never raw
        {{"bunny/../../escape", "x"}, "'..' leaves the folder"},
        {{"/etc/cron.d/x", "x"}, "'/etc/cron.d/x': an absolute"},
        {{"bunny/deep/runs.csv", "x"}, "deeper than CONFIG/FILE"},
        {{"top.csv", "x"}, "'top.csv': a file outside a config's folder"},
        {{"bunny/.hidden", "x"}, "'.hidden' is not a plain name"},
        {{"bunny/runs.csv", "y"}, "'bunny/runs.csv': a second entry of this name"},
        {{"bunny/sub", "", AE_IFDIR, 0755}, "a folder inside a config's folder"},
    };
    for (const auto& [member, why] : cases) {
        SCOPED_TRACE(member.path);
        fs::remove_all(out_);
        // A good file first: the refusal of a later entry must not leave it written.
        const std::string error = refusal({folder("bunny"), file("bunny/runs.csv"), member});
        EXPECT_THAT(error, HasSubstr("refused"));
        EXPECT_THAT(error, HasSubstr(why));
        EXPECT_THAT(error, HasSubstr("nothing unpacked"));
        EXPECT_FALSE(fs::exists(out_)) << "checked before anything is made";
    }
}

TEST_F(Unpack, TheCapsCountTheBytesRead) {
    EXPECT_THAT(refusal({folder("a"), file("a/big", std::string(1001, 'x'))}, {1000, 10000}),
                HasSubstr("'a/big': 1001 bytes, over the 1000-byte cap of a file"));
    EXPECT_THAT(refusal({folder("a"), file("a/one", std::string(600, 'x')), file("a/two", std::string(600, 'x'))}, {1000, 1000}),
                HasSubstr("'a/two': the archive unpacks to over 1000 bytes"));
    EXPECT_EQ(refusal({folder("a"), file("a/one", std::string(1000, 'x'))}, {1000, 1000}), "") << "at the cap: allowed";
}

TEST_F(Unpack, EntryAndFolderCapsCountTheArchive) {
    EXPECT_THAT(refusal({folder("a"), file("a/1"), file("a/2"), file("a/3")}, {1000, 10000, 3, 10}),
                HasSubstr("'a/3': over 3 entries"));
    EXPECT_THAT(refusal({folder("a"), folder("b"), file("c/1")}, {1000, 10000, 10, 2}), HasSubstr("'c/1': over 2 config folders"))
        << "a file's folder counts, listed or not";
    EXPECT_THAT(refusal({folder("a"), folder("b"), folder("c")}, {1000, 10000, 10, 2}), HasSubstr("'c': over 2 config folders"));
}

// A name in DIR that is a folder (or anything but a regular file) refuses the whole unpack before
// any file is put in place: the archive's other files are not half there.
TEST_F(Unpack, ATargetThatIsNoFileRefusesBeforeAnyRename) {
    writeArchive(archive_, {folder("bunny"), file("bunny/a.csv"), file("bunny/runs.csv")});
    fs::create_directories(out_ + "/bunny/runs.csv");
    try {
        unpackCampaign(archive_, out_);
        FAIL() << "unpacked over a folder";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("bunny/runs.csv: exists and is not a regular file"));
        EXPECT_THAT(e.what(), HasSubstr("nothing unpacked"));
    }
    EXPECT_FALSE(fs::exists(out_ + "/bunny/a.csv"));
    EXPECT_EQ(filesIn(out_), 0u) << "no temporary left";
}

TEST_F(Unpack, ATruncatedArchiveWritesNothing) {
    writeArchive(archive_, {folder("a"), file("a/one", std::string(100000, 'x')), file("a/two", std::string(100000, 'y'))}, true);
    fs::resize_file(archive_, 150000);  // inside a/two
    try {
        unpackCampaign(archive_, out_);
        FAIL() << "a truncated archive unpacked";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("refused"));
        EXPECT_THAT(e.what(), HasSubstr("nothing unpacked"));
    }
    EXPECT_FALSE(fs::exists(out_));
}

TEST_F(Unpack, NeverThroughALinkedFolderNorFromALinkOrFifo) {
    writeArchive(archive_, {folder("bunny"), file("bunny/runs.csv")});
    const std::string elsewhere = dir_.file("elsewhere");
    fs::create_directory(elsewhere);
    fs::create_directory_symlink(elsewhere, out_);
    EXPECT_THROW(
        try { unpackCampaign(archive_, out_); } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("is a symbolic link; refusing to unpack through it"));
            throw;
        },
        Error);
    fs::remove(out_);
    fs::create_directory(out_);
    fs::create_directory_symlink(elsewhere, out_ + "/bunny");  // a config's folder planted as a link
    EXPECT_THROW(
        try { unpackCampaign(archive_, out_); } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("bunny: is a symbolic link or not a folder"));
            throw;
        },
        Error);
    EXPECT_TRUE(fs::is_empty(elsewhere));
    fs::remove(out_ + "/bunny");
    const std::string linked = dir_.file("linked.tar.xz"), fifo = dir_.file("fifo.tar");
    fs::create_symlink(archive_, linked);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    EXPECT_THROW(unpackCampaign(linked, out_), Error);
    EXPECT_THROW(unpackCampaign(fifo, out_), Error) << "refused, not waited on";
    EXPECT_EQ(filesIn(out_), 0u);
}

}  // namespace
}  // namespace rtbench
