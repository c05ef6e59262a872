// Hit records (.hits) and `rtbench images` on hostile input: files of another run or size,
// truncated or oversized files, links and FIFOs, bad pixels; each bad file reported with its
// reason while the others are still converted; PNGs encoded in memory and written atomically.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "harness/images.h"
#include "harness/writers.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

#ifdef RTBENCH_WITH_OIIO
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#endif

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// A w x h image whose pixels differ: every kind of HitDiff, hits and misses.
HitImage pattern(std::uint32_t w, std::uint32_t h) {
    HitImage image;
    image.width = w;
    image.height = h;
    for (std::uint32_t i = 0; i < w * h; ++i) {
        image.diff.push_back(std::uint8_t(i % 5));
        image.shade.push_back(i % 3 == 0 ? -1.0f : float(i % 7) / 7.0f);
    }
    return image;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string le32(std::uint32_t v) {
    std::string s;
    for (int k = 0; k < 4; ++k) s += char((v >> (8 * k)) & 0xff);
    return s;
}
std::string le16(std::uint16_t v) {
    return std::string{char(v & 0xff), char(v >> 8)};
}
// A version-2 header as the format says, for hostile variants.
std::string headerV2(std::uint32_t w, std::uint32_t h, const std::string& run, const std::string& hash) {
    return "RTBHITS2" + le32(w) + le32(h) + le16(std::uint16_t(run.size())) + run + le16(std::uint16_t(hash.size())) + hash;
}
// The pixels of `image` as both versions store them.
std::string pixels(const HitImage& image) {
    std::string s;
    for (float f : image.shade) {
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        s += le32(bits);
    }
    s.append(image.diff.begin(), image.diff.end());
    return s;
}

TEST(HitRecords, Version2RoundTripsWithTheRunItBelongsTo) {
    TempDir dir;
    const HitImage image = pattern(7, 5);
    const std::string path = dir.file("run-007.hits");
    writeHitRecords(path, image, "007", "c0ffee0123456789");
    const std::string bytes = readBytes(path);
    // The layout of the format, byte for byte.
    EXPECT_EQ(bytes, headerV2(7, 5, "007", "c0ffee0123456789") + pixels(image));
    EXPECT_EQ(bytes.size(), 8u + 8 + 2 + 3 + 2 + 16 + 7 * 5 * 5);
    const HitImage back = readHitRecords(path);
    EXPECT_EQ(back.fileVersion, 2);
    EXPECT_EQ(back.run, "007");
    EXPECT_EQ(back.configHash, "c0ffee0123456789");
    EXPECT_EQ(back.width, 7u);
    EXPECT_EQ(back.height, 5u);
    EXPECT_EQ(back.shade, image.shade);
    EXPECT_EQ(back.diff, image.diff);
}

TEST(HitRecords, Version1FilesAreStillRead) {
    TempDir dir;
    const HitImage image = pattern(4, 3);
    const std::string path = dir.write("run-000.hits", "RTBHITS1" + le32(4) + le32(3) + pixels(image));
    const HitImage back = readHitRecords(path);
    EXPECT_EQ(back.fileVersion, 1);
    EXPECT_EQ(back.run, "");
    EXPECT_EQ(back.configHash, "");
    EXPECT_EQ(back.shade, image.shade);
    EXPECT_EQ(back.diff, image.diff);
    // ... with the same exact-size check.
    EXPECT_EQ(errorOf([&] { readHitRecords(dir.write("run-001.hits", "RTBHITS1" + le32(4) + le32(3) + "x")); }),
              dir.file("run-001.hits") + ": truncated: 17 bytes, but a header of 4 x 3 pixels needs exactly 16 + 5 x 12 = 76");
}

TEST(HitRecords, WriterRefusesWhatItCouldNotReadBack) {
    TempDir dir;
    const std::string path = dir.file("run-000.hits");
    EXPECT_THAT(errorOf([&] { writeHitRecords(path, pattern(2, 2), "", "abc"); }),
                HasSubstr("must be 1 to 64 printable characters"));
    EXPECT_THAT(errorOf([&] { writeHitRecords(path, pattern(2, 2), "000", std::string(65, 'a')); }),
                HasSubstr("must be 1 to 64 printable characters"));
    HitImage wrong = pattern(2, 2);
    wrong.width = 3;
    EXPECT_EQ(errorOf([&] { writeHitRecords(path, wrong, "000", "abc"); }),
              path + ": hit records of 3 x 2 pixels with 4 shades and 4 diffs");
    EXPECT_FALSE(fs::exists(path));
}

// A header claiming 2^32-1 x 2^32-1 pixels (or the largest legal image in a 40-byte file) is
// refused from the header and the file size, before anything is allocated.
TEST(HitRecords, AHeaderClaimingAHugeImageIsRefusedBeforeAllocating) {
    TempDir dir;
    const std::string huge = dir.write("run-000.hits", headerV2(0xffffffffu, 0xffffffffu, "000", "h") + "xxxx");
    EXPECT_EQ(errorOf([&] { readHitRecords(huge); }),
              huge + ": the header claims 4294967295 x 4294967295 pixels (allowed: 1 to 16384 a side, as camera.width "
                     "and camera.height)");
    const std::string zero = dir.write("run-001.hits", headerV2(0, 5, "001", "h"));
    EXPECT_THAT(errorOf([&] { readHitRecords(zero); }), HasSubstr("the header claims 0 x 5 pixels"));

    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    const std::string largest = dir.write("run-002.hits", headerV2(16384, 16384, "002", "h") + "xxxx");
    EXPECT_EQ(errorOf([&] { readHitRecords(largest); }),
              largest + ": truncated: 28 bytes, but a header of 16384 x 16384 pixels needs exactly 24 + 5 x 268435456 = "
                        "1342177304");
    getrusage(RUSAGE_SELF, &after);
    // 16384^2 pixels would take 1.3 GB; the refusal takes nothing of the kind (ru_maxrss in KiB).
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 64 * 1024) << "the reader allocated before checking the size";
}

TEST(HitRecords, TruncatedOrOverlongFilesNameTheSizesTheyShouldHave) {
    TempDir dir;
    const HitImage image = pattern(3, 2);
    const std::string good = headerV2(3, 2, "000", "abc") + pixels(image);
    const std::string cut = dir.write("run-000.hits", good.substr(0, good.size() - 1));
    EXPECT_EQ(errorOf([&] { readHitRecords(cut); }),
              cut + ": truncated: 55 bytes, but a header of 3 x 2 pixels needs exactly 26 + 5 x 6 = 56");
    const std::string longer = dir.write("run-001.hits", good + "!");
    EXPECT_EQ(errorOf([&] { readHitRecords(longer); }),
              longer + ": wrong size: 57 bytes, but a header of 3 x 2 pixels needs exactly 26 + 5 x 6 = 56");
    const std::string inHeader = dir.write("run-002.hits", good.substr(0, 20));
    EXPECT_EQ(errorOf([&] { readHitRecords(inHeader); }),
              inHeader + ": truncated: the file ends in the header, inside its run number");
    const std::string tiny = dir.write("run-003.hits", "RTBHITS2");
    EXPECT_EQ(errorOf([&] { readHitRecords(tiny); }),
              tiny + ": truncated: 8 bytes, shorter than a hit-record header (16 bytes)");
    const std::string inId = dir.write("run-004.hits", "RTBHITS2" + le32(1) + le32(1) + le16(40) + "00");
    EXPECT_EQ(errorOf([&] { readHitRecords(inId); }), inId + ": truncated: the file ends in the header, inside its run number");
    const std::string longId = dir.write("run-005.hits", "RTBHITS2" + le32(1) + le32(1) + le16(65) + std::string(80, '0'));
    EXPECT_EQ(errorOf([&] { readHitRecords(longId); }), longId + ": the header's run number has 65 bytes (allowed: 1 to 64)");
}

TEST(HitRecords, AFileOverTheSizeOfTheLargestImageIsRefusedNamingIt) {
    TempDir dir;
    const std::string path = dir.write("run-000.hits", headerV2(2, 2, "000", "abc"));
    fs::resize_file(path, kHitsMaxFileBytes + 1);  // sparse: no disk taken
    EXPECT_EQ(errorOf([&] { readHitRecords(path); }),
              path + ": hit-record file of 1342177429 bytes, more than the 1342177428 of the largest image (16384 x 16384)");
}

TEST(HitRecords, OtherFilesLinksAndFifosAreRefused) {
    TempDir dir;
    const std::string other = dir.write("run-000.hits", "P6\n3 2\n255\n" + std::string(18, '\0'));
    EXPECT_EQ(errorOf([&] { readHitRecords(other); }),
              other + ": not an rtbench hit-record file (its first 8 bytes are 'P6\\x0A3 2\\x0A2', expected 'RTBHITS2' or "
                      "'RTBHITS1')");
    writeHitRecords(dir.file("real.hits"), pattern(2, 2), "001", "abc");
    fs::create_symlink(dir.file("real.hits"), dir.file("run-001.hits"));
    EXPECT_EQ(errorOf([&] { readHitRecords(dir.file("run-001.hits")); }),
              dir.file("run-001.hits") + ": is a symbolic link (hit records are read only from regular files)");
    ASSERT_EQ(::mkfifo(dir.file("run-002.hits").c_str(), 0600), 0);
    EXPECT_EQ(errorOf([&] { readHitRecords(dir.file("run-002.hits")); }), dir.file("run-002.hits") + ": not a regular file");
    EXPECT_THAT(errorOf([&] { readHitRecords(dir.file("absent.hits")); }),
                StartsWith(dir.file("absent.hits") + ": cannot open hit records: No such file"));
}

TEST(HitRecords, PixelsOutsideTheirRangeAreRefused) {
    TempDir dir;
    HitImage image = pattern(3, 2);
    image.diff[4] = 9;
    const std::string badDiff = dir.write("run-000.hits", headerV2(3, 2, "000", "abc") + pixels(image));
    EXPECT_EQ(errorOf([&] { readHitRecords(badDiff); }),
              badDiff + ": pixel 4 (x 1, y 1) has diff value 9 (allowed: 0 to 4)");
    image = pattern(3, 2);
    image.shade[2] = std::numeric_limits<float>::quiet_NaN();
    const std::string nan = dir.write("run-001.hits", headerV2(3, 2, "001", "abc") + pixels(image));
    EXPECT_EQ(errorOf([&] { readHitRecords(nan); }),
              nan + ": pixel 2 (x 2, y 0) has shade nan (allowed: -1 for a miss, 0 to 1 for a hit)");
    image.shade[2] = 7.0f;
    const std::string big = dir.write("run-002.hits", headerV2(3, 2, "002", "abc") + pixels(image));
    EXPECT_THAT(errorOf([&] { readHitRecords(big); }), HasSubstr("pixel 2 (x 2, y 0) has shade 7.000000"));
}

// The writer never writes through a link at the path (writeFileAtomically refuses it, or
// replaces the link itself: either way the link's target keeps its bytes).
TEST(HitRecords, WritingNeverGoesThroughALink) {
    TempDir dir;
    const std::string victim = dir.write("victim", "keep me");
    fs::create_symlink(victim, dir.file("run-000.hits"));
    const std::string error = errorOf([&] { writeHitRecords(dir.file("run-000.hits"), pattern(2, 2), "000", "abc"); });
    EXPECT_EQ(readBytes(victim), "keep me");
    if (error == "(no error)") {
        EXPECT_FALSE(fs::is_symlink(dir.file("run-000.hits")));
        EXPECT_EQ(readHitRecords(dir.file("run-000.hits")).run, "000");
    } else {
        EXPECT_THAT(error, StartsWith(dir.file("run-000.hits") + ": is a symlink"));
    }
}

// ---- `rtbench images` on a folder -------------------------------------------------------------

class ImagesFolder : public ::testing::Test {
protected:
    void SetUp() override {
        if (!imagesSupported()) GTEST_SKIP() << "built without OpenImageIO";
    }
    // runs.csv with runs 000-006 (4 x 3 pixels, run 002 6 x 2), config hash "hash-NNN".
    void writeRuns() {
        std::vector<Row> rows;
        for (int r = 0; r < 7; ++r) {
            const std::string run = "00" + std::to_string(r);
            rows.push_back({{"run", run}, {"camera_width", r == 2 ? "6" : "4"}, {"camera_height", r == 2 ? "2" : "3"},
                            {"config_hash", "hash-" + run}, {"status", "ok"}});
        }
        writeCsv(dir_.file("runs.csv"), {"run", "camera_width", "camera_height", "config_hash", "status"}, rows);
    }
    std::string hits(const std::string& run, const HitImage& image, const std::string& hash) {
        writeHitRecords(dir_.file("run-" + run + ".hits"), image, run, hash);
        return dir_.file("run-" + run + ".hits");
    }
    bool pngs(const std::string& run) {
        return fs::exists(dir_.file("run-" + run + "-shaded.png")) && fs::exists(dir_.file("run-" + run + "-diff.png"));
    }
    TempDir dir_;
};

TEST_F(ImagesFolder, EachBadFileIsReportedWithItsReasonAndTheOthersAreStillDrawn) {
    writeRuns();
    hits("000", pattern(4, 3), "hash-000");                       // good
    const std::string truncated = hits("001", pattern(4, 3), "hash-001");
    fs::resize_file(truncated, 40);                               // truncated, first of the bad ones
    const std::string otherSize = hits("002", pattern(4, 3), "hash-002");  // the row says 6 x 2
    const std::string otherSweep = hits("003", pattern(4, 3), "hash-of-another-sweep");
    const std::string otherRun = dir_.file("run-004.hits");       // run 005's records, renamed
    writeHitRecords(otherRun, pattern(4, 3), "005", "hash-005");
    hits("005", pattern(4, 3), "hash-005");                       // good, after the bad ones
    dir_.write("run-006.hits", "RTBHITS1" + le32(4) + le32(3) + pixels(pattern(4, 3)));  // good, version 1
    const std::string noRow = hits("009", pattern(4, 3), "hash-009");
    const std::string badName = dir_.file("bunny.hits");
    writeHitRecords(badName, pattern(4, 3), "000", "hash-000");

    const ImagesReport report = imagesForFolder(dir_.path().string());
    EXPECT_EQ(report.written, 3);
    EXPECT_EQ(report.hitsFiles(), 9);
    EXPECT_THAT(report.failures,
                ::testing::ElementsAre(
                    badName + ": not named run-NNN.hits (the run number names its runs.csv row)",
                    truncated + ": truncated: 40 bytes, but a header of 4 x 3 pixels needs exactly 31 + 5 x 12 = 91",
                    otherSize + ": holds 4 x 3 pixels, but run 002 of runs.csv is 6 x 2",
                    otherSweep + ": holds hit records of config hash hash-of-another-sweep, but run 003 of runs.csv has "
                                 "config hash hash-003 (from another sweep?)",
                    otherRun + ": holds the hit records of run 005, not of run 004",
                    noRow + ": runs.csv has no row for run 009"));
    EXPECT_THAT(report.warnings, ::testing::ElementsAre(dir_.file("run-006.hits") +
                                                        ": a version 1 file (RTBHITS1): it records no run or config "
                                                        "hash, so only its name and size were checked against runs.csv"));
    EXPECT_TRUE(pngs("000"));
    EXPECT_TRUE(pngs("005"));
    EXPECT_TRUE(pngs("006"));
    for (const char* run : {"001", "002", "003", "004", "009"}) EXPECT_FALSE(pngs(run)) << run;

    // The all-or-nothing form says the same.
    const std::string all = errorOf([&] { writeImagesForFolder(dir_.path().string()); });
    EXPECT_THAT(all, StartsWith("6 of 9 hit-record files failed\n  " + badName + ": not named"));
    EXPECT_THAT(all, HasSubstr("\n  " + noRow + ": runs.csv has no row for run 009"));
}

TEST_F(ImagesFolder, AGoodFolderGivesTheCountAndPngsOfThePixels) {
    writeRuns();
    hits("000", pattern(4, 3), "hash-000");
    hits("002", pattern(6, 2), "hash-002");
    EXPECT_EQ(writeImagesForFolder(dir_.path().string()), 2);
#ifdef RTBENCH_WITH_OIIO
    // The diff PNG decodes to the colours of the pattern: red where only the kernel hit.
    auto in = OIIO::ImageInput::open(dir_.file("run-000-diff.png"));
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().width, 4);
    EXPECT_EQ(in->spec().height, 3);
    std::vector<std::uint8_t> rgb(4 * 3 * 3);
    ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data()));
    EXPECT_EQ(rgb[3 * 3 + 0], 255);  // pixel 3: OnlyKernelHit
    EXPECT_EQ(rgb[3 * 3 + 1], 0);
    EXPECT_EQ(rgb[4 * 3 + 2], 255);  // pixel 4: OnlyEmbreeHit, blue
#endif
}

TEST_F(ImagesFolder, WhatStopsThemAllIsOneError) {
    EXPECT_EQ(errorOf([&] { imagesForFolder(dir_.file("absent")); }),
              dir_.file("absent") + ": not a results folder (no such folder)");
    dir_.write("file", "x");
    EXPECT_EQ(errorOf([&] { imagesForFolder(dir_.file("file")); }), dir_.file("file") + ": not a results folder (not a folder)");
    hits("000", pattern(4, 3), "hash-000");
    EXPECT_EQ(errorOf([&] { imagesForFolder(dir_.path().string()); }),
              dir_.path().string() + ": no runs.csv to check the hit records against (for shards: rtbench merge first)");
    fs::remove(dir_.file("run-000.hits"));
    writeRuns();
    EXPECT_THAT(errorOf([&] { imagesForFolder(dir_.path().string()); }), HasSubstr(": no .hits files"));
}

// A folder holding a symlink is refused as `rtbench run` refuses it: nothing is written, and the
// link's target is untouched.
TEST_F(ImagesFolder, PngsNeverGoThroughALink) {
    writeRuns();
    hits("000", pattern(4, 3), "hash-000");
    hits("001", pattern(4, 3), "hash-001");
    const std::string victim = dir_.write("victim", "keep me");
    fs::create_symlink(victim, dir_.file("run-000-shaded.png"));
    EXPECT_THAT(errorOf([&] { imagesForFolder(dir_.path().string()); }),
                HasSubstr(dir_.file("run-000-shaded.png") + ": a symlink in the results folder"));
    EXPECT_EQ(readBytes(victim), "keep me");
    EXPECT_FALSE(pngs("001"));
}

TEST(Png, EncodedInMemoryWithoutTouchingTheNamedPath) {
    if (!imagesSupported()) {
        EXPECT_THAT(errorOf([] { encodePng(1, 1, {0, 0, 0}, "x.png"); }), HasSubstr("built without OpenImageIO"));
        return;
    }
    TempDir dir;
    const std::string bytes = encodePng(2, 1, {255, 0, 0, 0, 0, 255}, dir.file("only-a-name.png"));
    EXPECT_EQ(bytes.substr(0, 8), "\x89PNG\r\n\x1a\n");
    EXPECT_FALSE(fs::exists(dir.file("only-a-name.png")));
    EXPECT_EQ(errorOf([] { encodePng(2, 2, {1, 2, 3}, "x.png"); }), "x.png: a PNG of 2 x 2 needs 12 bytes of RGB, given 3");
}

TEST(Exr, EncodedInMemoryAndReadBackFloatForFloat) {
    if (!imagesSupported()) {
        EXPECT_THAT(errorOf([] { encodeExr(1, 1, {0.5f}, "x.exr"); }), HasSubstr("built without OpenImageIO"));
        return;
    }
    TempDir dir;
    const std::vector<float> grey = {0.0f, 0.25f, 1.0f / 3.0f, 0.999f, 1.0f, 0.125f};
    const std::string bytes = encodeExr(3, 2, grey, dir.file("only-a-name.exr"));
    EXPECT_EQ(bytes.substr(0, 4), "\x76\x2f\x31\x01");  // OpenEXR's magic number
    EXPECT_FALSE(fs::exists(dir.file("only-a-name.exr")));
    EXPECT_EQ(errorOf([] { encodeExr(2, 2, {1.0f}, "x.exr"); }), "x.exr: an EXR of 2 x 2 needs 4 values, given 1");
#ifdef RTBENCH_WITH_OIIO
    const std::string path = dir.write("back.exr", bytes);
    auto in = OIIO::ImageInput::open(path);
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().width, 3);
    EXPECT_EQ(in->spec().height, 2);
    ASSERT_EQ(in->spec().nchannels, 1);
    EXPECT_EQ(in->spec().channelnames[0], "Y");
    std::vector<float> back(6);
    ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, back.data()));
    EXPECT_EQ(back, grey);  // float stored as float: bit for bit
#endif
}

// writeImages with an EXR: the shades in float, a miss 0, beside the PNGs.
TEST(Exr, WrittenBesideThePngsWithTheShades) {
    if (!imagesSupported()) GTEST_SKIP() << "built without OpenImageIO";
    TempDir dir;
    const HitImage image = pattern(4, 3);
    writeImages(dir.file("run-000"), image, true);
    EXPECT_TRUE(fs::exists(dir.file("run-000-shaded.png")));
    EXPECT_TRUE(fs::exists(dir.file("run-000-diff.png")));
#ifdef RTBENCH_WITH_OIIO
    auto in = OIIO::ImageInput::open(dir.file("run-000-shaded.exr"));
    ASSERT_TRUE(in) << OIIO::geterror();
    std::vector<float> back(12);
    ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, back.data()));
    for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(back[i], image.shade[i] < 0.0f ? 0.0f : image.shade[i]) << i;
#endif
    writeImages(dir.file("run-001"), image);
    EXPECT_FALSE(fs::exists(dir.file("run-001-shaded.exr")));
}

}  // namespace
}  // namespace rtbench
