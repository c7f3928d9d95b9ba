// The words of a run configuration's enums (config.hpp): one table each, read by to_string, parse and words.
#include <hubbeam/config.hpp>

namespace hubbeam {

namespace {

const WordTable<Axial, 2> axial_words = {{Axial::dynamic, "dynamic"}, {Axial::quasi_static, "quasi-static"}};
const WordTable<Stepping, 2> stepping_words = {{Stepping::free, "free"}, {Stepping::rows, "rows"}};
const WordTable<ModelSource, 3> sources = {
    {ModelSource::automatic, "auto"}, {ModelSource::generated, "generated"}, {ModelSource::assembled, "assembled"}};
const WordTable<ErrorCheck, 3> error_check_words = {
    {ErrorCheck::on, "on"}, {ErrorCheck::off, "off"}, {ErrorCheck::full, "full"}};
const WordTable<SensitivityErrorControl, 2> sensitivity_control_words = {
    {SensitivityErrorControl::on, "on"}, {SensitivityErrorControl::off, "off"}};
const WordTable<OutputLoads, 2> loads_words = {{OutputLoads::none, "none"}, {OutputLoads::root, "root"}};
const WordTable<InitialState, 3> initial_words = {
    {InitialState::rest, "rest"}, {InitialState::static_equilibrium, "static"}, {InitialState::steady, "steady"}};

}  // namespace

std::string to_string(Axial v) { return word_of(v, axial_words); }
bool parse(std::string_view w, Axial& v) { return parse_word(w, axial_words, v); }
template <> std::vector<std::string> words<Axial>() { return all_words(axial_words); }
std::string to_string(Stepping v) { return word_of(v, stepping_words); }
bool parse(std::string_view w, Stepping& v) { return parse_word(w, stepping_words, v); }
template <> std::vector<std::string> words<Stepping>() { return all_words(stepping_words); }
std::string to_string(ModelSource v) { return word_of(v, sources); }
bool parse(std::string_view w, ModelSource& v) { return parse_word(w, sources, v); }
template <> std::vector<std::string> words<ModelSource>() { return all_words(sources); }
std::string to_string(ErrorCheck v) { return word_of(v, error_check_words); }
bool parse(std::string_view w, ErrorCheck& v) { return parse_word(w, error_check_words, v); }
template <> std::vector<std::string> words<ErrorCheck>() { return all_words(error_check_words); }
std::string to_string(SensitivityErrorControl v) { return word_of(v, sensitivity_control_words); }
bool parse(std::string_view w, SensitivityErrorControl& v) { return parse_word(w, sensitivity_control_words, v); }
template <> std::vector<std::string> words<SensitivityErrorControl>() { return all_words(sensitivity_control_words); }
std::string to_string(OutputLoads v) { return word_of(v, loads_words); }
bool parse(std::string_view w, OutputLoads& v) { return parse_word(w, loads_words, v); }
template <> std::vector<std::string> words<OutputLoads>() { return all_words(loads_words); }
std::string to_string(InitialState v) { return word_of(v, initial_words); }
bool parse(std::string_view w, InitialState& v) { return parse_word(w, initial_words, v); }
template <> std::vector<std::string> words<InitialState>() { return all_words(initial_words); }

}  // namespace hubbeam

namespace hubbeam {

double Rotor::azimuth(int b) const
{
    return 2.0 * 3.14159265358979323846 * b / blades;
}

Parameters Rotor::blade(const Parameters& p, int b) const
{
    Parameters out = p;
    if (!pitch_offsets.empty()) out.pitch += pitch_offsets.at(static_cast<std::size_t>(b));
    if (!tip_masses.empty()) out.m_tip = tip_masses.at(static_cast<std::size_t>(b));
    if (b > 0) {  // the hub's inertia, translating mass and support once, with blade 1
        out.J_oh = 0.0;
        out.m_hub = out.k_x = out.k_y = out.c_x = out.c_y = 0.0;
    }
    return out;
}

}  // namespace hubbeam
