// On-demand variants (runtime/include/hubbeam/on_demand.hpp): compiled once into the cache, reused, safe when two
// compilations race, and equal to the hand-assembled equations.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <hubbeam/make_model.hpp>
#include <hubbeam/model.hpp>
#include <hubbeam/on_demand.hpp>
#include <iterator>
#include <optional>
#include <random>
#include <string>

#include "generated_abi.h"
#include "models/generated_model.hpp"
#include "random_state.hpp"

using namespace hubbeam;
using namespace hubbeam::test;
namespace fs = std::filesystem;

TEST_CASE("an on-demand variant is compiled once, even by two racing callers, then loaded from the cache",
          "[on_demand]")
{
    const fs::path root = fs::temp_directory_path() / ("hubbeam-test-cache-" + std::to_string(::getpid()));
    fs::remove_all(root);
    ::setenv("HUBBEAM_CACHE_DIR", root.c_str(), 1);
    const VariantKey key = VariantKey::parse("amm_nx1_ny3_torque_first");  // not built in
    Parameters p;
    p.a = 0.35;

    // Two callers at once: the variant's file lock lets one compile; the other waits and loads its object.
    const auto make = [&] { return make_model(key, p, ModelSource::generated); };
    auto first = std::async(std::launch::async, make), second = std::async(std::launch::async, make);
    const std::unique_ptr<Model> a = first.get(), b = second.get();
    INFO("origins: " << a->origin() << " / " << b->origin());
    CHECK(a->origin().rfind("compiled now", 0) == 0);
    CHECK(b->origin().rfind("compiled now", 0) == 0);

    // The cache holds the object, its checksum record and its lock file, nothing else: the work folders are gone.
    std::vector<std::string> entries;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root))
        entries.push_back(fs::relative(e.path(), root).string());
    std::sort(entries.begin(), entries.end());
    const fs::path version = variant_cache_dir().filename();
    CHECK(entries == std::vector<std::string>{version.string(), (version / ("." + key.name() + ".lock")).string(),
                                              (version / (key.name() + ".so")).string(),
                                              (version / (key.name() + ".so.sha256")).string()});
    // Created private; the record is the object's SHA-256 as an independent tool computes it.
    CHECK((fs::status(root).permissions() & fs::perms::all) == fs::perms::owner_all);
    CHECK((fs::status(root / version).permissions() & fs::perms::all) == fs::perms::owner_all);
    const fs::path object = root / version / (key.name() + ".so");
    std::string sum;
    {
        const std::string command = "sha256sum '" + object.string() + "'";
        FILE* pipe = ::popen(command.c_str(), "r");
        REQUIRE(pipe != nullptr);
        char line[256] = {};
        if (std::fgets(line, sizeof line, pipe) != nullptr) sum = std::string(line).substr(0, 64);
        ::pclose(pipe);
    }
    std::ifstream record(root / version / (key.name() + ".so.sha256"));
    std::string recorded((std::istreambuf_iterator<char>(record)), std::istreambuf_iterator<char>());
    CHECK(recorded == "sha256 " + sum + " size " + std::to_string(fs::file_size(object)) + "\n");
    CHECK(cached_variant_names() == std::vector<std::string>{key.name()});

    // A later request loads it without compiling, and it computes the same equations as the assembled path.
    bool noted = false;
    const auto c = make_model(key, p, ModelSource::automatic, [&](const std::string&) { noted = true; });
    CHECK(c->origin() == "cached");
    CHECK_FALSE(noted);
    const auto assembled = make_model(key, p, ModelSource::assembled);
    std::mt19937 rng(11);
    const int n = key.nq();
    for (int trial = 0; trial < 3; ++trial) {
        const State s = random_state(key, rng);
        Eigen::MatrixXd M(n, n), M_ref(n, n);
        Eigen::VectorXd Q(n), Q_ref(n);
        for (const Model* m : {a.get(), b.get(), c.get()}) {
            m->mass(s.u, s.q.data(), M.data());
            m->forces(s.u, s.q.data(), s.qd.data(), Q.data());
            assembled->mass(s.u, s.q.data(), M_ref.data());
            assembled->forces(s.u, s.q.data(), s.qd.data(), Q_ref.data());
            CHECK((M - M_ref).lpNorm<Eigen::Infinity>() <= 1e-12 * M_ref.lpNorm<Eigen::Infinity>());
            CHECK((Q - Q_ref).lpNorm<Eigen::Infinity>() <= 1e-12 * Q_ref.lpNorm<Eigen::Infinity>());
        }
    }
    fs::remove_all(root);
}

TEST_CASE("a table row of another interface version or variant is refused before any kernel is called",
          "[on_demand][abi]")
{
    const VariantKey key = VariantKey::parse("amm_nx4_ny4_prescribed_first");
    const generated::Variant* built_in = built_in_variant(key);
    REQUIRE(built_in != nullptr);
    CHECK(built_in->abi_version == generated::abi_version);
    CHECK(row_problem(*built_in, key).empty());
    generated::Variant older = *built_in;
    older.abi_version = generated::abi_version - 1;
    CHECK_THAT(row_problem(older, key), Catch::Contains("built by an older generator (interface version " +
                                                        std::to_string(generated::abi_version - 1)));
    CHECK_THAT(row_problem(*built_in, VariantKey::parse("amm_nx4_ny4_torque_first")),
               Catch::Contains("does not hold variant amm_nx4_ny4_torque_first"));
}

/// Sets an environment variable for one scope and puts back what it was.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name)
    {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value, 1);
    }
    ~ScopedEnv()
    {
        if (old_)
            ::setenv(name_, old_->c_str(), 1);
        else
            ::unsetenv(name_);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

TEST_CASE("HUBBEAM_CXXFLAGS reach the compiler, key a cache folder of their own, and a word that is no option is "
          "refused",
          "[on_demand]")
{
    const fs::path root = fs::temp_directory_path() / ("hubbeam-test-flags-" + std::to_string(::getpid()));
    fs::remove_all(root);
    const ScopedEnv cache("HUBBEAM_CACHE_DIR", root.c_str());
    const VariantKey key = VariantKey::parse("amm_nx1_ny2_torque_first");  // not built in
    Parameters p;
    p.a = 0.35;
    fs::path plain;
    {
        const ScopedEnv none("HUBBEAM_CXXFLAGS", "");
        plain = variant_cache_dir();
        CHECK(on_demand_flags().empty());
    }
    CHECK(plain == root / generator_version());

    SECTION("other options, another folder; the same options, the same folder")
    {
        const ScopedEnv flags("HUBBEAM_CXXFLAGS", " -O1  -DHUBBEAM_TEST ");
        CHECK(on_demand_flags() == "-O1 -DHUBBEAM_TEST");
        const fs::path dir = variant_cache_dir();
        CHECK(dir.parent_path() == root);
        CHECK(dir.filename().string().rfind(generator_version() + "-flags-", 0) == 0);
        const ScopedEnv again("HUBBEAM_CXXFLAGS", "-O1 -DHUBBEAM_TEST");
        CHECK(variant_cache_dir() == dir);
        const ScopedEnv other("HUBBEAM_CXXFLAGS", "-O2 -DHUBBEAM_TEST");
        CHECK(variant_cache_dir() != dir);
    }
    SECTION("the compiler sees them: an option it does not know fails the compile, naming it")
    {
        const ScopedEnv flags("HUBBEAM_CXXFLAGS", "-fno-such-option-for-hubbeam");
        CHECK_THROWS_WITH(make_model(key, p, ModelSource::generated),
                          Catch::Contains("compiling " + key.name() + " failed") &&
                              Catch::Contains("-fno-such-option-for-hubbeam"));
        CHECK_FALSE(fs::exists(variant_cache_dir() / (key.name() + ".so")));
    }
    SECTION("a bare word, or an option that moves or changes the output, is refused before anything is compiled")
    {
        for (const char* bad : {"-O1 extra.cpp", "-o x.so", "-ox.so", "-c", "-E", "-S", "-"}) {
            INFO(bad);
            const ScopedEnv flags("HUBBEAM_CXXFLAGS", bad);
            CHECK_THROWS_AS(variant_cache_dir(), CompileError);
            CHECK_THROWS_WITH(make_model(key, p, ModelSource::generated),
                              Catch::Contains("HUBBEAM_CXXFLAGS: expected compiler options"));
        }
    }
    fs::remove_all(root);
}
