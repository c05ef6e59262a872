// Typed columns (schema/column.h): how a declared column writes its values, against hand-written
// cells, and that the columns of runs.csv carry the type their declaration gives them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>

#include "harness/columns.h"
#include "schema/column.h"

namespace rtbench {
namespace {

TEST(Column, WritesEachValueAsItsTypeIs) {
    Row row;
    const Column<double> ratio({"ratio", ColumnKind::Exact, "", "a number"}, 4);
    const Column<double> mean({"mean", ColumnKind::Exact, "", "a number"});
    const Column<std::uint64_t> bytes({"bytes", ColumnKind::Exact, "bytes", "a count"});
    const Column<std::string> label({"label", ColumnKind::Exact, "", "a name"});
    put(row, ratio, 1.23456789);
    put(row, mean, 1.23456789);
    // The largest count a uint64 holds, digit for digit: no pass through a double (2^64 - 1 would
    // round to 1.84467e+19).
    put(row, bytes, std::numeric_limits<std::uint64_t>::max());
    put(row, label, std::string("bunny, 512x512"));
    EXPECT_EQ(row.at("ratio"), "1.235");
    EXPECT_EQ(row.at("mean"), "1.23457");
    EXPECT_EQ(row.at("bytes"), "18446744073709551615");
    EXPECT_EQ(row.at("label"), "bunny, 512x512");
    EXPECT_EQ(bytes.spec().type, ColumnType::Integer);
    EXPECT_EQ(ratio.spec().type, ColumnType::Number);
    EXPECT_EQ(label.spec().type, ColumnType::Text);
}

TEST(Column, NoValueIsAnEmptyCellNeverZero) {
    Row row;
    const Column<double> cv({"cv", ColumnKind::Timing, "", "a spread"}, 4);
    put(row, cv, std::optional<double>());
    EXPECT_EQ(row.at("cv"), "");
    put(row, cv, std::optional<double>(0.125));
    EXPECT_EQ(row.at("cv"), "0.125");
}

TEST(Column, AGroupListsItsColumnsInTheOrderDeclared) {
    struct Declared {
        ColumnGroup group;
        Column<unsigned> first = group.add<unsigned>({"first", ColumnKind::Exact, "cells", "one"});
        Column<double> second = group.add<double>({"second", ColumnKind::Exact, "fraction", "two"}, 3);
    } declared;
    ASSERT_EQ(declared.group.specs().size(), 2u);
    EXPECT_EQ(declared.group.specs()[0].name, "first");
    EXPECT_EQ(declared.group.specs()[1].name, "second");
    EXPECT_EQ(declared.group.specs()[1].type, ColumnType::Number);
}

// runs.csv's columns as their parts declare them: the grid's and the architecture's typed
// columns keep their place and carry their declared type. The static instruction estimates are
// counts: integers (until schema 28's columns.csv inferred "number" from their unit).
TEST(Column, RunsColumnsCarryTheirDeclaredTypes) {
    EXPECT_EQ(columnSpec("grid_res_x").type, ColumnType::Integer);
    EXPECT_EQ(columnSpec("grid_empty_fraction").type, ColumnType::Number);
    EXPECT_EQ(columnSpec("grid_voxel_margin").appliesWhen.front(), "structure.type=uniform_grid");
    EXPECT_EQ(columnSpec("instructions_total").type, ColumnType::Integer);
    EXPECT_EQ(columnSpec("instructions_per_byte").type, ColumnType::Number);
    EXPECT_EQ(columnSpec("instructions_total").since, 17);
    EXPECT_EQ(columnSpec("simd_lane_utilisation").since, 14);
    EXPECT_EQ(columnSpec("bytes_compaction").since, 13);
    const std::vector<std::string> names = runColumns();
    const auto at = [&](const std::string& name) { return std::find(names.begin(), names.end(), name) - names.begin(); };
    EXPECT_EQ(at("triangles_per_ray_mean"), at("work_per_ray_mean") + 1);
    EXPECT_EQ(at("instructions_per_step"), at("bytes_per_ray") + 1);
}

}  // namespace
}  // namespace rtbench
