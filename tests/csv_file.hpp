// A numeric CSV file a test reads back (a run's rows, a fields CSV): its header's names and its rows of numbers.
#pragma once

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace hubbeam::test {

/// One CSV file as its header's names and its rows of numbers.
struct Csv {
    std::vector<std::string> names;
    std::vector<std::vector<double>> rows;
    std::size_t column(const std::string& name) const
    {
        for (std::size_t i = 0; i < names.size(); ++i)
            if (names[i] == name) return i;
        FAIL("no column " << name);
        return 0;
    }
};

inline Csv read_csv(const std::string& path)
{
    std::ifstream in(path);
    REQUIRE(in);
    Csv csv;
    std::string line, cell;
    std::getline(in, line);
    for (std::istringstream s(line); std::getline(s, cell, ',');) csv.names.push_back(cell);
    while (std::getline(in, line)) {
        std::vector<double> row;
        for (std::istringstream s(line); std::getline(s, cell, ',');) row.push_back(std::stod(cell));
        csv.rows.push_back(row);
    }
    return csv;
}

}  // namespace hubbeam::test
