// A runs.csv column declared beside the code that computes its value (nvbench's way: a
// measurement with its metadata where it is recorded): its spec (name, kind, unit, meaning,
// schema) and the C++ type of its value, which fixes how every value is written and the type
// columns.csv gives the column. `put` is the one way a typed value reaches a row.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "columns.h"

namespace rtbench {

// What columns.csv calls a column holding T: integers (counts, bytes), numbers, text.
template <class T>
constexpr ColumnType columnTypeOf() {
    static_assert(!std::is_same_v<T, bool>, "a flag column: declare it as an integer 0/1 or add a boolean format");
    if constexpr (std::is_integral_v<T>)
        return ColumnType::Integer;
    else if constexpr (std::is_floating_point_v<T>)
        return ColumnType::Number;
    else {
        static_assert(std::is_same_v<T, std::string>, "a column holds an integer, a number or text");
        return ColumnType::Text;
    }
}

template <class T>
class Column {
public:
    // `digits`: the significant digits a number is written with (formatNumber).
    explicit Column(ColumnSpec spec, int digits = 6) : spec_(std::move(spec)), digits_(digits) { spec_.type = columnTypeOf<T>(); }
    const ColumnSpec& spec() const { return spec_; }
    const std::string& name() const { return spec_.name; }
    std::string format(const T& value) const {
        if constexpr (std::is_integral_v<T>)
            return std::to_string(value);
        else if constexpr (std::is_floating_point_v<T>)
            return formatNumber(double(value), digits_);
        else
            return value;
    }

private:
    ColumnSpec spec_;
    int digits_;
};

// A part's columns in the order it declares them, each declared once: members of a struct
// initialised in turn, `ColumnGroup group;` first.
class ColumnGroup {
public:
    template <class T>
    Column<T> add(ColumnSpec spec, int digits = 6) {
        Column<T> column(std::move(spec), digits);
        specs_.push_back(column.spec());
        return column;
    }
    const std::vector<ColumnSpec>& specs() const { return specs_; }

private:
    std::vector<ColumnSpec> specs_;
};

// The column's cell in the row: the value written as its type is everywhere.
template <class T>
void put(Row& row, const Column<T>& column, const std::type_identity_t<T>& value) {
    row[column.name()] = column.format(value);
}

// Empty where there is no value (never 0: a spread of one sample, a count a method does not keep).
template <class T>
void put(Row& row, const Column<T>& column, const std::optional<T>& value) {
    row[column.name()] = value ? column.format(*value) : "";
}

}  // namespace rtbench
