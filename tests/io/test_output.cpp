// CsvWriter: rows buffered and written in chunks at most 0.1 s apart, into a temporary file renamed over the
// target at the end (by finish() or the destructor); OutputFile's refusals, lock and failed writes; the checks of
// a command's outputs by file identity; and Simulation::run stopping between rows when asked.
#include <catch2/catch.hpp>

#include <bit>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>
#include <string>
#include <random>
#include <thread>

#include <csignal>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <hubbeam/scene.hpp>
#include <hubbeam/simulate.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/shortest.hpp>

using namespace hubbeam;
namespace fs = std::filesystem;

namespace {

/// A fresh directory for one test case, removed with everything in it afterwards.
struct ScratchDir {
    fs::path dir = fs::temp_directory_path() / ("hubbeam_test_output_" + std::to_string(::getpid()));
    ScratchDir()
    {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~ScratchDir() { fs::remove_all(dir); }
    std::string operator/(const std::string& name) const { return (dir / name).string(); }
};

std::string contents(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void put(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

/// The pid of a process that has ended: it names no process until the kernel hands it out again.
pid_t ended_process()
{
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    REQUIRE(pid > 0);
    REQUIRE(::waitpid(pid, nullptr, 0) == pid);
    return pid;
}

Row row_at(double t) { return {t, 2 * t, 3.0, -t, 1e-300, 0.1, 0.3, 1e20, -0.0, 12345.678}; }

/// What the file should hold after the header and these rows.
std::string expected(std::initializer_list<double> times)
{
    std::string s = std::string(row_header()) + "\n";
    for (double t : times) s += csv_line(row_at(t)) + "\n";
    return s;
}

/// An .npy file as this test reads it, written from the format's description (numpy's NEP 1), not from the writer.
struct Npy {
    std::string dict;          // the header's dict, as written
    long rows = -1, columns = -1;
    std::vector<double> data;  // row after row
};

/// Reads a format 1.0 .npy file of little-endian doubles in C order; fails the test on anything else.
Npy read_npy(const std::string& path)
{
    const std::string bytes = contents(path);
    REQUIRE(bytes.size() >= 10);
    REQUIRE(bytes.substr(0, 8) == std::string("\x93NUMPY\x01\x00", 8));
    const std::size_t dict_size = static_cast<unsigned char>(bytes[8]) + 256u * static_cast<unsigned char>(bytes[9]);
    REQUIRE(bytes.size() >= 10 + dict_size);
    CHECK((10 + dict_size) % 64 == 0);  // numpy aligns the data to 64 bytes
    Npy npy;
    npy.dict = bytes.substr(10, dict_size);
    CHECK(npy.dict.back() == '\n');
    CHECK(npy.dict.find("'descr': '<f8'") != std::string::npos);
    CHECK(npy.dict.find("'fortran_order': False") != std::string::npos);
    const std::size_t shape = npy.dict.find("'shape': (");
    REQUIRE(shape != std::string::npos);
    char* end = nullptr;
    npy.rows = std::strtol(npy.dict.c_str() + shape + 10, &end, 10);
    REQUIRE(std::string_view(end, 2) == ", ");
    npy.columns = std::strtol(end + 2, &end, 10);
    REQUIRE(*end == ')');
    const std::string data = bytes.substr(10 + dict_size);
    REQUIRE(data.size() == static_cast<std::size_t>(npy.rows * npy.columns) * 8);
    for (std::size_t i = 0; i < data.size(); i += 8) {
        std::uint64_t bits = 0;
        for (int b = 7; b >= 0; --b) bits = bits << 8 | static_cast<unsigned char>(data[i + b]);
        npy.data.push_back(std::bit_cast<double>(bits));
    }
    return npy;
}

/// A CSV table's numbers read with strtod, row after row (the header line skipped).
std::vector<double> csv_numbers(const std::string& path, long& rows)
{
    std::istringstream in(contents(path));
    std::string line;
    std::getline(in, line);
    std::vector<double> v;
    rows = 0;
    while (std::getline(in, line)) {
        ++rows;
        for (const char* p = line.c_str(); *p != '\0';) {
            char* end = nullptr;
            v.push_back(std::strtod(p, &end));
            p = *end == ',' ? end + 1 : end;
        }
    }
    return v;
}

/// Whether a and b hold the same doubles, bit for bit (-0 is not 0).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b)
{
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
    return true;
}

}  // namespace

TEST_CASE("CsvWriter leaves the old file until finish(), then replaces it whole", "[output]")
{
    const ScratchDir scratch;
    const std::string target = scratch / "out.csv";
    put(target, "old contents\n");
    CsvWriter csv(target);
    csv.write(row_at(0.0));
    csv.write(row_at(0.5));
    // The rows live in the temporary file, next to the target and named after it and this process.
    CHECK(csv.writing_path() == scratch / (".out.csv.tmp-" + std::to_string(::getpid())));
    CHECK(fs::exists(csv.writing_path()));
    CHECK(contents(target) == "old contents\n");
    REQUIRE(csv.finish());
    CHECK(contents(target) == expected({0.0, 0.5}));
    CHECK(csv.rows() == 2);
    CHECK_FALSE(fs::exists(csv.writing_path()));
    CHECK(std::distance(fs::directory_iterator(scratch.dir), fs::directory_iterator()) == 1);
}

TEST_CASE("CsvWriter buffers rows and writes them at the latest 0.1 s after the previous chunk", "[output]")
{
    const ScratchDir scratch;
    CsvWriter csv(scratch / "out.csv");
    const std::string header = expected({});
    CHECK(contents(csv.writing_path()) == header);  // written at once: an unwritable output shows at row 0
    csv.write(row_at(0.0));
    CHECK(contents(csv.writing_path()) == header);  // buffered, not a write per row
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    csv.write(row_at(1.0));
    CHECK(contents(csv.writing_path()) == expected({0.0, 1.0}));
}

TEST_CASE("CsvWriter: a second writer of one path is refused while the first writes", "[output]")
{
    const ScratchDir scratch;
    const std::string target = scratch / "out.csv";
    CsvWriter first(target);
    CHECK_THROWS_MATCHES(CsvWriter(target), OutputRefused,
                         Catch::Message("another hubbeam is writing " + target + " (it holds " +
                                        scratch / ".out.csv.lock" +
                                        "): wait for it to finish, or write to another file"));
    for (int i = 0; i < 3000; ++i) first.write(row_at(i));  // several chunks
    REQUIRE(first.finish());
    std::string all = expected({});
    for (int i = 0; i < 3000; ++i) all += csv_line(row_at(i)) + "\n";
    CHECK(contents(target) == all);
    // The lock is gone with the writer: nothing but the CSV is left, and the next writer may start.
    CHECK(std::distance(fs::directory_iterator(scratch.dir), fs::directory_iterator()) == 1);
    CsvWriter next(target);
    CHECK(next.finish());
}

TEST_CASE("CsvWriter puts the file in place when destroyed without finish() (a run ended by an exception)",
          "[output]")
{
    const ScratchDir scratch;
    const std::string target = scratch / "out.csv";
    {
        CsvWriter csv(target);
        csv.write(row_at(0.25));
    }
    CHECK(contents(target) == expected({0.25}));
}

TEST_CASE("CsvWriter writes each number in its shortest round-trip form", "[output]")
{
    const ScratchDir scratch;
    const std::string target = scratch / "out.csv";
    const double big = std::numeric_limits<double>::max(), tiny = std::numeric_limits<double>::denorm_min();
    {
        CsvWriter csv(target);
        csv.write({0.03, -big, tiny, -0.0, 1.0 / 3.0, 1e21, 100.0, -1e-7, 0.1 + 0.2, 7.0});
    }
    CHECK(contents(target) == std::string(row_header()) + "\n" +
                                  "0.03,-1.7976931348623157e+308,5e-324,-0,0.3333333333333333,1e+21,100,-1e-07,"
                                  "0.30000000000000004,7\n");
}

TEST_CASE("write_shortest writes std::to_chars's text, which reads back as the same double", "[output]")
{
    // libstdc++'s to_chars is the independent path: every value must come out byte for byte as it writes it.
    long checked = 0;
    std::string first_mismatch;
    const auto check = [&](double v) {
        char ours[shortest_room], theirs[64];
        const char* end = write_shortest(ours, v);
        const char* their_end = std::to_chars(theirs, theirs + sizeof theirs, v).ptr;
        ++checked;
        if (std::string_view(ours, end - ours) != std::string_view(theirs, their_end - theirs) &&
            first_mismatch.empty())
            first_mismatch = std::string(theirs, their_end - theirs) + " written as " + std::string(ours, end - ours);
        if (std::isfinite(v)) {
            double back = 0.0;
            std::from_chars(ours, end, back);
            if (std::bit_cast<std::uint64_t>(back) != std::bit_cast<std::uint64_t>(v) && first_mismatch.empty())
                first_mismatch = std::string(ours, end - ours) + " does not read back";
        }
    };
    std::mt19937_64 random(20261123);
    for (int i = 0; i < 300000; ++i) check(std::bit_cast<double>(random()));  // every exponent, sign, nan
    // Short decimals (the multiples of dt_out, round parameters), 1 to 17 digits at every decimal exponent.
    for (int i = 0; i < 300000; ++i) {
        const int digits = 1 + static_cast<int>(random() % 17), exponent = static_cast<int>(random() % 640) - 330;
        const std::string text = std::to_string(random() % static_cast<std::uint64_t>(std::pow(10.0, digits))) +
                                 "e" + std::to_string(exponent);
        double v = 0.0;
        std::from_chars(text.data(), text.data() + text.size(), v);
        check(v);
        check(-v);
    }
    // Powers of two (whose rounding interval is narrower below) and their neighbours, subnormals to the largest.
    for (int e = -1074; e <= 1023; ++e)
        for (int d = -2; d <= 2; ++d) check(std::bit_cast<double>(std::bit_cast<std::uint64_t>(std::ldexp(1.0, e)) + d));
    // Rows' times and round values: integers, multiples of 0.01 and 0.001, binary fractions, the plain/scientific
    // boundaries (0.001 against 1e-04, 12300000 against 1.23e+07), around 2^53.
    for (int i = -20000; i <= 20000; ++i) {
        check(i * 0.01);
        check(i * 0.001);
        check(i / 1024.0);
        check(static_cast<double>(i));
        check(i * 1e5);
        check(9007199254740992.0 + i);
    }
    for (const double v : {0.0, -0.0, 1e-4, 1.5e-4, 0.001, 0.00123, 1e15, 1e16, 1e21, 1e22, 1e23, 12300000.0,
                           123456789012345680000.0, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308,
                           std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()})
        check(v);
    CHECK(first_mismatch == "");
    CHECK(checked > 1000000);
}

TEST_CASE("An .npy output holds the CSV's numbers as doubles, its names beside it, in place only at finish()",
          "[output]")
{
    const ScratchDir scratch;
    const std::string target = scratch / "run.npy", names = scratch / "run.columns.txt";
    CHECK(is_npy_path(target));
    CHECK_FALSE(is_npy_path(scratch / "run.csv"));
    CHECK(npy_columns_path(target) == names);
    put(target, "old contents\n");
    const ColumnSet columns{0b10001};  // tau and work
    const std::vector<double> times = {0.0, 0.5, 1.0};
    {
        CsvWriter npy(target, columns);
        for (double t : times) npy.write(row_at(t));
        CHECK(contents(target) == "old contents\n");
        CHECK_FALSE(fs::exists(names));
        REQUIRE(npy.finish());
        CHECK(npy.rows() == 3);
    }
    const Npy a = read_npy(target);
    CHECK(a.rows == 3);
    CHECK(a.columns == static_cast<long>(row_width + 2));
    // The same numbers as the CSV lines of these rows, read back with strtod: the round trip both promise.
    std::vector<double> expected_values;
    for (double t : times) {
        const std::string line = csv_line(row_at(t), columns) + ",";
        for (const char* p = line.c_str(); *p != '\0';) {
            char* end = nullptr;
            expected_values.push_back(std::strtod(p, &end));
            p = end + 1;
        }
    }
    CHECK(same_bits(a.data, expected_values));
    CHECK(contents(names) == row_header(columns) + "\n");
    CHECK(std::distance(fs::directory_iterator(scratch.dir), fs::directory_iterator()) == 2);  // no lock, no temp

    // Rows that could not be kept (discard) leave the old file and no names.
    fs::remove(names);
    const std::string before = contents(target);
    {
        CsvWriter npy(target, columns);
        npy.write(row_at(2.0));
        npy.discard();
    }
    CHECK(contents(target) == before);
    CHECK_FALSE(fs::exists(names));
    CHECK_THROWS_AS(CsvWriter(target, columns).write_line("1,2"), std::logic_error);
}

TEST_CASE("A run stopped early to .npy counts its rows in the header and equals the CSV of the same run",
          "[output]")
{
    // One run feeds both writers: the .npy must hold exactly the numbers the CSV's text reads back as, and its
    // header the rows there are (written at the end, not guessed from t_end / dt_out at the start).
    const ScratchDir scratch;
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/damped_appendage.toml", {{"output.t_end", "2"}});
    const ColumnSet columns = optional_columns_of(scene);
    REQUIRE(columns.count() > 0);
    CsvWriter csv(scratch / "run.csv", columns), npy(scratch / "run.npy", columns);
    long rows = 0;
    const RunSummary summary = Simulation(scene).run(
        [&](const Row& r) {
            csv.write(r);
            npy.write(r);
            ++rows;
        },
        [&]() -> const char* { return rows == 37 ? "asked to stop" : nullptr; });
    CHECK_FALSE(summary.completed);
    REQUIRE(csv.finish());
    REQUIRE(npy.finish());
    long csv_rows = 0;
    const std::vector<double> from_text = csv_numbers(scratch / "run.csv", csv_rows);
    const Npy a = read_npy(scratch / "run.npy");
    CHECK(csv_rows == 37);
    CHECK(a.rows == 37);
    CHECK(a.columns == static_cast<long>(row_width + columns.count()));
    CHECK(same_bits(a.data, from_text));
    CHECK(contents(scratch / "run.columns.txt") == row_header(columns) + "\n");
}

TEST_CASE("OutputFile::write_at overwrites in place - durable or not, commit() puts the file in place", "[output]")
{
    const ScratchDir scratch;
    for (const bool durable : {false, true}) {
        const std::string target = scratch / (durable ? "durable.txt" : "plain.txt");
        OutputFile file(target);
        file.set_durable(durable);
        REQUIRE(file.write("abcdef") == 0);
        REQUIRE(file.write_at(2, "XY") == 0);
        CHECK_FALSE(fs::exists(target));
        CHECK(file.commit() == "");
        CHECK(contents(target) == "abXYef");
    }
}

TEST_CASE("CsvWriter refuses a target it cannot create, leaving nothing behind", "[output]")
{
    const ScratchDir scratch;
    const std::string target = scratch / "no_such_dir/out.csv";
    CHECK_THROWS_WITH(CsvWriter(target), Catch::StartsWith(target + ": cannot open for writing: No such file"));
    CHECK(std::distance(fs::directory_iterator(scratch.dir), fs::directory_iterator()) == 0);
}

TEST_CASE("OutputFile: a failed write leaves the old file and no temporary file", "[output]")
{
    // A full disk, simulated by a file size limit: write() fails with EFBIG (SIGXFSZ ignored, else it kills).
    const ScratchDir scratch;
    const std::string target = scratch / "out.csv";
    put(target, "old contents\n");
    struct rlimit old_limit {};
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    std::string error;
    {
        OutputFile file(target);
        struct rlimit small = old_limit;
        small.rlim_cur = 4096;
        REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
        const int first = file.write(std::string(4000, 'x'));
        const int second = file.write(std::string(4000, 'y'));
        ::setrlimit(RLIMIT_FSIZE, &old_limit);
        CHECK(first == 0);
        CHECK(second == EFBIG);
        CHECK(file.write("z") == EFBIG);  // nothing after a failure
        error = file.commit();
    }
    std::signal(SIGXFSZ, old_handler);
    CHECK(error == "write failed: File too large");
    CHECK(contents(target) == "old contents\n");
    CHECK(std::distance(fs::directory_iterator(scratch.dir), fs::directory_iterator()) == 1);
}

TEST_CASE("OutputFile: an abandoned file is removed and the target kept", "[output]")
{
    const ScratchDir scratch;
    const std::string target = scratch / "out.csv";
    put(target, "old contents\n");
    {
        OutputFile file(target);
        CHECK(file.write("new") == 0);
    }
    CHECK(contents(target) == "old contents\n");
    CHECK(std::distance(fs::directory_iterator(scratch.dir), fs::directory_iterator()) == 1);
}

TEST_CASE("OutputFile refuses a FIFO, a device and a directory without opening them", "[output]")
{
    const ScratchDir scratch;
    const std::string fifo = scratch / "fifo";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    // Opening a FIFO for writing would block here until a reader came.
    CHECK_THROWS_MATCHES(OutputFile(fifo), OutputRefused,
                         Catch::Message(fifo + ": expected a regular file or the name of a new one, got a FIFO"));
    CHECK_THROWS_AS(OutputFile("/dev/null"), OutputRefused);
    CHECK_THROWS_AS(OutputFile(scratch.dir.string()), OutputRefused);
    CHECK(not_a_regular_file(fifo) == "a FIFO");
    CHECK(not_a_regular_file("/dev/null") == "a character device");
    CHECK(not_a_regular_file(scratch.dir.string()) == "a directory");
    CHECK(not_a_regular_file(scratch / "new.csv").empty());
    CHECK(std::distance(fs::directory_iterator(scratch.dir), fs::directory_iterator()) == 1);  // the FIFO alone
}

TEST_CASE("same_file and check_outputs compare files, not spellings", "[output]")
{
    const ScratchDir scratch;
    const std::string scene = scratch / "scene.toml";
    put(scene, "[beam]\n");
    fs::create_directory(scratch.dir / "sub");
    fs::create_hard_link(scene, scratch.dir / "link.toml");
    CHECK(same_file(scene, scratch / "sub/../scene.toml"));
    CHECK(same_file(scene, scratch / "link.toml"));
    CHECK(same_file(scratch / "new.csv", scratch / "sub/../new.csv"));  // a file that does not exist yet
    CHECK_FALSE(same_file(scratch / "new.csv", scratch / "other.csv"));
    CHECK_FALSE(same_file(scratch / "new.csv", scratch / "no_such_dir/new.csv"));
    CHECK_THROWS_MATCHES(check_outputs({{scene, "the scene itself"}}, {{scratch / "link.toml", "-o"}}), OutputRefused,
                         Catch::Message("-o: expected a file other than the scene itself, got \"" +
                                        scratch / "link.toml" + "\""));
    CHECK_THROWS_MATCHES(check_outputs({}, {{scratch / "out.csv", "-o"}, {scratch / "sub/../out.csv", "--fields"}}),
                         OutputRefused,
                         Catch::Message("--fields: expected a file other than -o's \"" + scratch / "out.csv" +
                                        "\", got \"" + scratch / "sub/../out.csv" + "\""));
    CHECK_THROWS_WITH(check_outputs({}, {{scratch / "no_such_dir/out.csv", "-o"}}),
                      scratch / "no_such_dir/out.csv" + ": cannot open for writing: No such file or directory");
    CHECK_NOTHROW(check_outputs({{scene, "the scene itself"}}, {{scratch / "out.csv", "-o"}, {"", "--fields"}}));
}

TEST_CASE("OutputFile removes the temporary files of a writer that was killed, and only those", "[output]")
{
    ScratchDir scratch;
    const std::string out = scratch / "out.csv";
    const pid_t dead = ended_process();
    const std::string stale = scratch / (".out.csv.tmp-" + std::to_string(dead));
    const std::string stale_n = stale + "-1";
    const std::string alive = scratch / (".out.csv.tmp-" + std::to_string(::getppid()));  // a live process's
    const std::string other = scratch / (".other.csv.tmp-" + std::to_string(dead));     // another target's
    const std::string lock = scratch / ".out.csv.lock";                                 // held by nobody
    for (const std::string& f : {stale, stale_n, alive, other, lock}) put(f, "left by a killed writer\n");
    OutputFile file(out);
    REQUIRE(file.write("new\n") == 0);
    REQUIRE(file.commit().empty());
    CHECK(contents(out) == "new\n");
    CHECK_FALSE(fs::exists(stale));
    CHECK_FALSE(fs::exists(stale_n));
    CHECK_FALSE(fs::exists(lock));
    CHECK(fs::exists(alive));
    CHECK(fs::exists(other));
}

TEST_CASE("OutputFile reads the folder for a killed writer's files only where its lock file shows one", "[output]")
{
    // A writer removes its lock file as it finishes, so without one no writer was killed holding it: a temporary
    // file there is one a failed rename left on purpose (the message names it as the complete file), kept.
    ScratchDir scratch;
    const pid_t dead = ended_process();
    const std::string kept = scratch / (".out.csv.tmp-" + std::to_string(dead));
    put(kept, "the complete file of a rename that failed\n");
    OutputFile file(scratch / "out.csv");
    REQUIRE(file.write("new\n") == 0);
    REQUIRE(file.commit().empty());
    CHECK(fs::exists(kept));
    CHECK_FALSE(fs::exists(scratch / ".out.csv.lock"));
}

TEST_CASE("OutputFile refuses a symbolic link and a file its owner made read-only, leaving both alone", "[output]")
{
    ScratchDir scratch;
    const std::string target = scratch / "target.csv", link = scratch / "link.csv", kept = scratch / "kept.csv";
    put(target, "old\n");
    fs::create_symlink(target, link);
    CHECK_THROWS_MATCHES(OutputFile(link), OutputRefused,
                         Catch::Matchers::Message(link + " is a symbolic link: hubbeam does not write through a link; "
                                                         "name the file itself or choose another output"));
    CHECK_THROWS_AS(check_outputs({}, {{link, "-o"}}), OutputRefused);
    put(kept, "old\n");
    ::chmod(kept.c_str(), 0444);
    const std::string why = kept + " is read-only (mode 0444): hubbeam does not replace a file you protected; chmod "
                                   "u+w it or choose another output";
    CHECK_THROWS_MATCHES(OutputFile(kept), OutputRefused, Catch::Matchers::Message(why));
    CHECK_THROWS_MATCHES(check_outputs({}, {{kept, "-o"}}), OutputRefused, Catch::Matchers::Message("-o: " + why));
    CHECK(contents(target) == "old\n");
    CHECK(contents(kept) == "old\n");
    CHECK(fs::is_symlink(link));
    CHECK(fs::directory_iterator(scratch.dir) != fs::directory_iterator());
    for (const auto& e : fs::directory_iterator(scratch.dir))
        CHECK(e.path().filename().string().front() != '.');  // no temporary or lock file left
}

TEST_CASE("commit_together puts a set in place only when every file is whole", "[output]")
{
    ScratchDir scratch;
    const std::string a = scratch / "a.csv", b = scratch / "b.csv";
    put(a, "old a\n");
    put(b, "old b\n");
    {
        OutputFile fa(a), fb(b);
        REQUIRE(fa.write("new a\n") == 0);
        fb.fail("write failed: No space left on device");
        const std::string why = commit_together({&fa, &fb});
        CHECK(why == b + ": write failed: No space left on device (nothing written: the old files are as they were)");
    }
    CHECK(contents(a) == "old a\n");
    CHECK(contents(b) == "old b\n");
    OutputFile fa(a), fb(b);
    REQUIRE(fa.write("new a\n") == 0);
    REQUIRE(fb.write("new b\n") == 0);
    CHECK(commit_together({&fa, &fb}).empty());
    CHECK(contents(a) == "new a\n");
    CHECK(contents(b) == "new b\n");
}

TEST_CASE("Simulation::run stops between rows when its StopRequest asks", "[output]")
{
    const Scene scene = load_scene(HUBBEAM_SOURCE_DIR "/cases/spinup_omega4.toml", {{"output.t_end", "1"}});
    std::vector<Row> rows;
    const RunSummary summary =
        Simulation(scene).run([&](const Row& r) { rows.push_back(r); },
                              [&]() -> const char* { return rows.size() == 5 ? "asked to stop" : nullptr; });
    CHECK_FALSE(summary.completed);
    CHECK(summary.failure == "asked to stop");
    REQUIRE(rows.size() == 5);
    CHECK(summary.t_reached == rows.back().t);
}
