// hubbeam._core: the Python module's C++ side (pybind11). Runs scenes given as TOML text into one numpy array
// per run (rows appended in C++ with the GIL released, handed to numpy without a copy), and computes modes and
// linearized models; runtime/python/hubbeam/__init__.py gives them their Python shape.
//
// Threads and the GIL: long work runs without the GIL and asks between rows or spin rates whether to stop (Ctrl-C
// in the main thread, a cancelled sweep, an exiting interpreter). pybind11's gil_scoped_* classes are not used: a
// daemon thread that asks for the GIL while the interpreter finalizes is ended by Python with pthread_exit, whose
// unwinding through their noexcept destructors aborts the process; WithoutGil and WithGil park such a thread instead.
#include <cxxabi.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <hubbeam/hubbeam.hpp>
#include <hubbeam/make_model.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <variant>
#include <vector>

#include <hubbeam/modes_table.hpp>
#include <hubbeam/metadata.hpp>
#include <hubbeam/output.hpp>
#include <hubbeam/output_file.hpp>
#include <hubbeam/scene_print.hpp>
#include <hubbeam/on_demand.hpp>
#include <hubbeam/printable.hpp>
#include <hubbeam/shortest.hpp>

namespace py = pybind11;
using namespace hubbeam;

namespace {

/// True once the interpreter finalizes; an atomic of the runtime, read without the GIL.
bool finalizing()
{
#if PY_VERSION_HEX >= 0x030D0000
    return Py_IsFinalizing() != 0;
#else
    return _Py_IsFinalizing() != 0;
#endif
}

/// Where a thread that outlived the interpreter (a daemon thread) waits for the process to end: it touches nothing of
/// Python's and unwinds nothing.
[[noreturn]] void park()
{
    for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
}

/// The GIL released for a scope and taken back at its end, or the thread parked if the interpreter finalizes
/// meanwhile.
class WithoutGil {
public:
    WithoutGil() : state_(PyEval_SaveThread()) {}
    ~WithoutGil()
    {
        if (finalizing()) park();
        try {
            PyEval_RestoreThread(state_);
        } catch (abi::__forced_unwind&) {  // finalizing began while this thread waited for the GIL
            park();
        }
    }
    WithoutGil(const WithoutGil&) = delete;
    WithoutGil& operator=(const WithoutGil&) = delete;

private:
    PyThreadState* state_;
};

/// The GIL for a scope in a thread that runs without it (a callback from the integration), or the thread parked if
/// the interpreter finalizes.
class WithGil {
public:
    WithGil()
    {
        if (finalizing()) park();
        try {
            state_ = PyGILState_Ensure();
        } catch (abi::__forced_unwind&) {
            park();
        }
    }
    ~WithGil() { PyGILState_Release(state_); }
    WithGil(const WithGil&) = delete;
    WithGil& operator=(const WithGil&) = delete;

private:
    PyGILState_STATE state_{};
};

/// Raised by cancel_runs(): a cancellable computation (a sweep's point) stops at its next check once this has changed
/// since its start (an interrupted sweep's local workers are threads of this process: they stop instead of running
/// on).
std::atomic<long> cancel_generation{0};
/// Set by interrupt_runs(), for good: every computation of this process stops at its next check and raises
/// KeyboardInterrupt (the interpreter exits after Ctrl-C and would otherwise wait for its threads' runs to end).
std::atomic<bool> exiting{false};

/// Why a long computation stops early, asked between its rows or spin rates from the computing thread without the
/// GIL: Ctrl-C (Python runs signal handlers in the main thread only: that thread takes the GIL for a moment every
/// 0.1 s to let them run), a cancelled sweep, an exiting interpreter.
class Interrupts {
public:
    /// With the GIL, in the thread that computes; cancellable: a sweep's point, which cancel_runs() stops.
    explicit Interrupts(bool cancellable)
        : generation_(cancellable ? cancel_generation.load() : -1),
          main_thread_(PyThread_get_thread_ident() ==
                       py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>())
    {
    }

    /// nullptr to go on, or why the computation stops.
    const char* reason()
    {
        if (generation_ >= 0 && cancel_generation.load() != generation_) return "cancelled: the sweep was interrupted";
        if (exiting.load() || finalizing()) {
            exit_ = true;
            return "interrupted: the interpreter is exiting";
        }
        if (!main_thread_) return nullptr;
        const auto now = std::chrono::steady_clock::now();
        if (now - asked_ < std::chrono::milliseconds(100)) return nullptr;
        asked_ = now;
        const WithGil gil;
        if (PyErr_CheckSignals() != 0) {  // the handler's exception (KeyboardInterrupt) stays set for raise()
            signalled_ = true;
            return "interrupted by signal";
        }
        return nullptr;
    }

    /// With the GIL, once the computation has returned: raises what stopped it, unless a cancelled sweep did.
    void raise() const
    {
        if (signalled_) throw py::error_already_set();
        if (exit_) {
            PyErr_SetString(PyExc_KeyboardInterrupt, "the interpreter is exiting");
            throw py::error_already_set();
        }
    }

private:
    long generation_;
    bool main_thread_;
    bool signalled_ = false, exit_ = false;
    std::chrono::steady_clock::time_point asked_ = std::chrono::steady_clock::now();
};

/// Scene keys set from Python: (dotted key, its value as the command line types it, the keyword that set it).
using Keywords = std::vector<std::tuple<std::string, std::string, std::string>>;

/// The keyword that set key, for messages: a Python user wrote ny=..., not --ny.
std::string keyword_of(const Keywords& keywords, const std::string& key)
{
    for (const auto& [k, value, keyword] : keywords)
        if (k == key) return keyword;
    return "";
}

/// The scene with the keywords' keys set: the file at `text` when name is empty, else `text` itself (a scene written
/// in code, named name in messages). Bad input raises ValueError with the command line's message, against the
/// keyword where one set the key.
Scene scene_of(const std::string& text, const std::string& name, const Keywords& keywords)
{
    Overrides overrides;
    for (const auto& [key, value, keyword] : keywords) overrides.emplace_back(key, value);
    try {
        return name.empty() ? load_scene(text, overrides) : parse_scene(text, name, overrides);
    } catch (const SceneError& e) {
        const std::string keyword = keyword_of(keywords, e.key);
        throw py::value_error(keyword.empty() ? e.what() : keyword + ": " + e.problem());
    }
}

/// sensitivities= of hubbeam.run set on the scene: refused where the scene or a key already names other parameters
/// (one of them would be dropped silently).
void set_sensitivities(Scene& scene, const std::vector<std::string>& names, const Keywords& keywords)
{
    const auto sorted = [](std::vector<std::string> v) {
        std::sort(v.begin(), v.end());
        return v;
    };
    if (!scene.output.sensitivities.empty() && sorted(scene.output.sensitivities) != sorted(names)) {
        const auto listed = [](const std::vector<std::string>& v) {
            std::string out;
            for (const std::string& n : v) out += (out.empty() ? "" : ",") + n;
            return "\"" + printable(out, 200) + "\"";
        };
        const std::string keyword = keyword_of(keywords, "output.sensitivities");
        throw py::value_error("sensitivities: got " + listed(names) + " where " +
                              (keyword.empty() ? printable(scene.path, 400) + " sets output.sensitivities"
                                               : "the keyword " + keyword + " sets output.sensitivities") +
                              " = " + listed(scene.output.sensitivities) +
                              ": expected one of the two, or the same parameters in both");
    }
    scene.output.sensitivities = names;
    try {
        validate(scene);
    } catch (const SceneError& e) {
        throw py::value_error((e.key == "output.sensitivities" ? "sensitivities: " + e.problem() : e.what()));
    }
}

/// What a spin rate the model has no steady state at (the axial stretch diverges) raises: ValueError naming omega,
/// as for any other rate the function cannot take.
template <class Compute>
auto at_spin(double omega, const Compute& compute)
{
    try {
        return compute();
    } catch (const CompileError&) {
        throw;
    } catch (const std::runtime_error& e) {
        throw py::value_error("omega: expected a spin rate the scene's beam has a steady state at, got " +
                              shortest(omega) + " rad/s: " + e.what());
    }
}

/// A model for the scene's variant, or ValueError / RuntimeError as hubbeam run exits 2.
template <class Make>
auto guarded(const Scene& scene, const Make& make)
{
    try {
        return make();
    } catch (const std::invalid_argument& e) {
        throw py::value_error(scene.path + ": " + e.what());
    } catch (const CompileError& e) {
        throw std::runtime_error(e.what());
    }
}

/// The rows as an n x width array that owns them (no copy: the vector moves into the capsule).
py::array_t<double> rows_array(std::vector<double>&& rows, std::size_t width)
{
    auto* owned = new std::vector<double>(std::move(rows));
    py::capsule free_rows(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    const auto n = static_cast<py::ssize_t>(owned->size() / width);
    return py::array_t<double>(
        {n, static_cast<py::ssize_t>(width)},
        {static_cast<py::ssize_t>(width * sizeof(double)), static_cast<py::ssize_t>(sizeof(double))}, owned->data(),
        free_rows);
}

/// f() with its thread parked if Python code it runs ends the thread. Python code may drop the GIL, and a daemon
/// thread that asks for it back while the interpreter finalizes is ended with pthread_exit: its unwinding must meet no
/// destructor that touches a Python object without the GIL (pybind11's objects and argument tuples do), so f holds
/// Python objects by plain pointers only and the unwinding stops here.
template <class F>
auto parked_on_exit(F f)
{
    try {
        return f();
    } catch (abi::__forced_unwind&) {
        park();
    }
}

/// f(t, state) with state a dict of s: the result (a new reference), or nullptr with the Python error set.
PyObject* call_law(PyObject* f, double t, const HubState& s)
{
    return parked_on_exit([&]() -> PyObject* {
        PyObject* state = Py_BuildValue("{s:d,s:d,s:d,s:d}", "theta", s.theta, "theta_dot", s.theta_dot, "tip_uy",
                                        s.tip_uy, "tip_uy_dot", s.tip_uy_dot);
        if (state == nullptr) return nullptr;
        return PyObject_CallFunction(f, "dN", t, state);  // N: the call owns state
    });
}

/// o's attribute where it is a text, else repr(o) ("?" where both fail); both may run Python code.
std::string name_of(PyObject* o, const char* attribute)
{
    return parked_on_exit([&] {
        PyObject* r = attribute != nullptr ? PyObject_GetAttrString(o, attribute) : nullptr;
        if (r == nullptr || !PyUnicode_Check(r)) {
            Py_XDECREF(r);
            PyErr_Clear();
            r = PyObject_Repr(o);
        }
        const char* text = r != nullptr ? PyUnicode_AsUTF8(r) : nullptr;
        std::string out = text != nullptr ? text : "?";
        Py_XDECREF(r);
        PyErr_Clear();
        return out;
    });
}

/// A Python callable f(t, state) -> tau as a torque law: state is a dict with theta, theta_dot, tip_uy and
/// tip_uy_dot. Each call takes the GIL (the integration runs without it). An exception in f, or a result that is no
/// real number (int, float, or numpy's), is kept for the caller to raise (the latter as a TypeError naming f and what
/// it returned) and makes the torque NaN, which stops the run at once.
TorqueLaw python_law(py::object f, std::shared_ptr<std::exception_ptr> failure)
{
    const py::module_ numpy = py::module_::import("numpy");
    struct Held {
        py::object f, integer, floating;
    };
    auto held = std::make_shared<Held>(Held{std::move(f), numpy.attr("integer"), numpy.attr("floating")});
    return [held, failure](double t, const HubState& s) -> double {
        const WithGil gil;
        if (*failure) return std::numeric_limits<double>::quiet_NaN();
        try {
            const auto tau = py::reinterpret_steal<py::object>(call_law(held->f.ptr(), t, s));
            if (!tau) throw py::error_already_set();
            PyObject* p = tau.ptr();
            if (PyFloat_Check(p)) return PyFloat_AS_DOUBLE(p);
            // A bool is an int to Python, a complex number has a float() in numpy: neither is a torque. The checks
            // run no Python code (numpy's scalar types have no __instancecheck__).
            if ((PyLong_Check(p) && !PyBool_Check(p)) ||
                PyObject_TypeCheck(p, reinterpret_cast<PyTypeObject*>(held->integer.ptr())) ||
                PyObject_TypeCheck(p, reinterpret_cast<PyTypeObject*>(held->floating.ptr()))) {
                const double value = PyFloat_AsDouble(p);
                if (value == -1.0 && PyErr_Occurred()) throw py::error_already_set();
                return value;
            }
            const std::string type = Py_TYPE(p)->tp_name;  // a built-in type's is module.name: its __name__ follows
            throw py::type_error("torque law " + printable(name_of(held->f.ptr(), "__qualname__"), 120) + " returned " +
                                 printable(name_of(p, nullptr), 120) + " (" +
                                 printable(type.substr(type.rfind('.') + 1), 80) +
                                 "): expected a real number, the hub torque in N m");
        } catch (...) {
            *failure = std::current_exception();
            return std::numeric_limits<double>::quiet_NaN();
        }
    };
}

/// The files a scene was read from, as scene_inputs names them for check_outputs: (path, name) pairs, which
/// Result.save hands back so that it never replaces one of them.
std::vector<std::pair<std::string, std::string>> inputs_of(const Scene& scene)
{
    std::vector<std::pair<std::string, std::string>> out;
    for (const NamedPath& p : scene_inputs(scene)) out.emplace_back(p.path, p.name);
    return out;
}

/// A run's summary as the Python result's attributes (the command line's summary lines, and its text).
py::dict summary_dict(const RunSummary& s, const Scene& scene)
{
    py::dict out;
    out["columns"] = row_header();
    out["variant"] = s.variant;
    out["source"] = s.source;
    out["algebra"] = s.algebra;
    out["stepper"] = s.stepper;
    out["stepper_why"] = s.stepper_why;
    out["newton"] = s.newton;
    out["completed"] = s.completed;
    out["failure"] = s.failure;
    out["t_reached"] = s.t_reached;
    out["max_abs_tip_uy"] = s.max_abs_tip_uy;
    out["t_steady"] = s.t_steady;
    out["jacobi_drift"] = s.jacobi_drift;
    out["vibration_energy"] = s.vibration_energy;
    out["energy_balance"] = s.energy_balance;
    out["monitor_off"] = s.monitor_off;
    out["estimated_error"] = s.estimated_error;
    out["error_column"] = s.error_column;
    out["error_from"] = s.error_from;
    out["steps"] = s.steps;
    out["rejected_steps"] = s.rejected_steps;
    out["rhs_evals"] = s.rhs_evals;
    out["jacobian_evals"] = s.jacobian_evals;
    out["wall_seconds"] = s.wall_seconds;
    out["check_wall_seconds"] = s.check_wall_seconds;
    out["summary_text"] = format_summary(s, scene);
    return out;
}

/// One run: the rows as an array and the summary's fields (hubbeam.run).
py::dict run(const std::string& text, const std::string& name, const Keywords& keywords, bool cancellable,
             const py::object& torque, const std::optional<std::vector<std::string>>& sensitivities)
{
    Interrupts interrupts(cancellable);
    // What hubbeam run does in process, timed the same way: load, choose the model, integrate.
    const auto start = std::chrono::steady_clock::now();
    Scene scene = scene_of(text, name, keywords);
    if (sensitivities) set_sensitivities(scene, *sensitivities, keywords);
    const auto law_failure = std::make_shared<std::exception_ptr>();
    if (!torque.is_none()) {
        if (!PyCallable_Check(torque.ptr()))
            throw py::value_error("torque: expected a callable f(t, state) -> tau (N m), got " +
                                  printable(py::str(py::repr(torque)).cast<std::string>()));
        Control c;  // the hub is free, driven by f; the scene's motion and [control] are not used
        c.law = python_law(torque, law_failure);
        scene.control = std::move(c);
    }
    const ColumnSet columns = optional_columns_of(scene);
    const std::size_t width = row_width + columns.count();
    std::unique_ptr<Simulation> simulation;
    {
        // Choosing the model may compile a variant for seconds: a sweep's other worker threads run meanwhile.
        const WithoutGil release;
        simulation = guarded(scene, [&] { return std::make_unique<Simulation>(scene); });
    }
    std::vector<double> rows;
    RunSummary s;
    const StopRequest stop = [&interrupts] { return interrupts.reason(); };
    {
        // The integration touches no Python object (but the torque law's): other Python threads run meanwhile.
        const WithoutGil release;
        rows.reserve(width * static_cast<std::size_t>(std::min(1e7, scene.output.t_end / scene.output.dt_out + 2.0)));
        s = simulation->run(
            [&rows, &columns](const Row& r) { for_each_value(r, columns, [&rows](double v) { rows.push_back(v); }); },
            stop);
    }
    interrupts.raise();  // Ctrl-C or an exiting interpreter: KeyboardInterrupt; a cancelled sweep's point: its rows
    if (*law_failure) std::rethrow_exception(*law_failure);  // the torque law's own exception
    const double in_process = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    py::dict out = summary_dict(s, scene);
    out["columns"] = row_header(columns);
    // Where the rows came from, as hubbeam run writes it beside its output (Result.save names the file).
    out["metadata"] = run_metadata(scene, s, "", row_header(columns), static_cast<long>(rows.size() / width));
    out["scene_file"] = scene.path;
    out["inputs"] = inputs_of(scene);
    out["data"] = rows_array(std::move(rows), width);
    out["in_process_seconds"] = in_process;
    return out;
}

/// The block of the scene's variant (hubbeam modes' own assembly), computed without the GIL and stopped between
/// spin rates when interrupts say so.
/// frame= as hubbeam.modes and hubbeam.linearize take it: "" (fixed where multi-blade coordinates apply), "fixed"
/// (ValueError where they do not, naming why) or "rotating".
Frame frame_of(const Scene& scene, const std::string& text)
{
    Frame frame = Frame::fixed;
    if (!text.empty() && !parse(text, frame))
        throw py::value_error("frame: expected \"fixed\" or \"rotating\", got " + printable(text));
    if (!text.empty() && frame == Frame::fixed)
        if (const std::string why = fixed_frame_refusal(scene); !why.empty()) throw py::value_error("frame: " + why);
    return frame;
}

ModesBlock modes_of(const Scene& scene, const std::vector<double>& omegas, const std::vector<int>& harmonics,
                    Interrupts& interrupts, Frame frame)
{
    struct Stopped {
        const char* why;
    };  // thrown by the check between spin rates: no std::exception, so nothing on the way catches it
    try {
        const WithoutGil release;
        const VariantKey key = scene.key();
        const std::unique_ptr<Model> model =
            guarded(scene, [&] { return make_scene_model(scene, key); });
        const auto check = [&interrupts] {
            if (const char* why = interrupts.reason()) throw Stopped{why};
        };
        try {
            return modes_block(*model, key, scene, omegas, harmonics, check, frame);
        } catch (const std::runtime_error&) {
            // Name the rate that has no steady state (ValueError) if that is what failed; a rate with no steady state
            // under the weight in the plane has its periodic motion's Floquet modes instead, whose failure is its own.
            for (const double w : omegas)
                if (unsteady_spin(key, scene.parameters.packed(), w).empty() || multiblade(scene, frame))
                    at_spin(w, [&] { return steady_spin(*model, w, scene.motion.initial_theta()); });
            throw;
        }
    } catch (const Stopped& stopped) {
        interrupts.raise();
        throw std::runtime_error(stopped.why);  // a cancelled sweep's point
    }
}

/// One column's cells of rows, each a T.
template <class T, class Row>
std::vector<T> cells(const TableColumn<Row>& column, const ModesBlock& block, const std::vector<Row>& rows)
{
    std::vector<T> values;
    values.reserve(rows.size());
    for (const Row& r : rows) values.push_back(std::get<T>(column.cell(block, r)));
    return values;
}

/// A table's columns, but the variant's, as entries of out by their names: numbers and integers as numpy arrays,
/// texts as lists of str.
template <class Row>
void add_columns(py::dict& out, const std::vector<TableColumn<Row>>& columns, const ModesBlock& block,
                 const std::vector<Row>& rows)
{
    for (const TableColumn<Row>& column : columns) {
        if (column.of_variant) continue;
        const TableCell kind = column.cell(block, Row{});
        if (std::holds_alternative<double>(kind))
            out[column.name] = py::array(py::cast(cells<double>(column, block, rows)));
        else if (std::holds_alternative<int>(kind))
            out[column.name] = py::array(py::cast(cells<int>(column, block, rows)));
        else
            out[column.name] = cells<std::string>(column, block, rows);
    }
}

/// Every mode of the scene's variant at each spin rate: columns of equal length, and the critical speeds'.
py::dict modes(const std::string& text, const std::string& name, const Keywords& keywords,
               const std::vector<double>& omegas, const std::vector<int>& harmonics, bool cancellable,
               const std::string& frame)
{
    Interrupts interrupts(cancellable);
    const Scene scene = scene_of(text, name, keywords);
    const ModesBlock block = modes_of(scene, omegas, harmonics, interrupts, frame_of(scene, frame));
    py::dict out;
    out["variant"] = block.key.name();
    out["scene_file"] = scene.path;
    add_columns(out, modes_columns(), block, block.modes);
    py::dict critical;
    add_columns(critical, critical_columns(), block, block.critical);
    out["critical"] = critical;
    return out;
}

/// An Eigen matrix as a new numpy array.
py::array_t<double> matrix(const Eigen::MatrixXd& m)
{
    py::array_t<double> a({m.rows(), m.cols()});
    auto v = a.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < m.rows(); ++i)
        for (Eigen::Index j = 0; j < m.cols(); ++j) v(i, j) = m(i, j);
    return a;
}

/// The scene's model, chosen without the GIL: choosing it may compile a variant for seconds.
std::unique_ptr<Model> model_without_gil(const Scene& scene)
{
    const WithoutGil release;
    return guarded(scene, [&] { return make_scene_model(scene); });
}

/// The state-space matrices and their names about the steady spin omega; a controlled hub's closed loop and open
/// loop (hubbeam.linearize).
py::dict linearize(const std::string& text, const std::string& name, const Keywords& keywords, double omega,
                   const std::string& frame)
{
    const Scene scene = scene_of(text, name, keywords);
    const VariantKey key = scene.key();
    const bool coleman = multiblade(scene, frame_of(scene, frame));
    const std::unique_ptr<Model> model = model_without_gil(scene);
    const StateSpace open = at_spin(omega, [&] {
        // A balanced rotor on a moving hub spins steadily, but its blades' frames see periodic equations.
        if (const std::string why = unsteady_spin(key, scene.parameters.packed(), omega); !coleman && !why.empty())
            throw std::invalid_argument(why);
        const SteadySpin steady = steady_spin(*model, omega, scene.motion.initial_theta());
        return coleman ? multiblade_state_space(*model, steady) : state_space(*model, steady);
    });
    // A controlled hub: the closed loop (input: a torque added to the controller's), and under "open" the hub
    // without its controller (input tau), as `hubbeam linearize` writes PREFIX-* and PREFIX-open-*.
    const auto system = [](const StateSpace& ss) {
        py::dict out;
        out["A"] = matrix(ss.A);
        out["B"] = matrix(ss.B);
        out["C"] = matrix(ss.C);
        out["D"] = matrix(ss.D);
        out["states"] = ss.states;
        out["inputs"] = ss.inputs;
        out["outputs"] = ss.outputs;
        return out;
    };
    py::dict out = system(scene.control ? closed_loop(open, *scene.control) : open);
    out["variant"] = key.name();
    if (scene.control) out["open"] = system(open);
    return out;
}

/// The blade's mode shapes at the steady spin omega and their ElastoDyn polynomials (hubbeam modes --elastodyn):
/// under BldFl1Sh, BldFl2Sh and BldEdgSh the mode's name, frequency, coefficients of x^2 .. x^6, fit residual and
/// samples; the file's section as text. ValueError for a variant without flapwise coordinates or a rate without a
/// steady state.
py::dict elastodyn_shapes(const std::string& text, const std::string& name, const Keywords& keywords, double omega)
{
    const Scene scene = scene_of(text, name, keywords);
    const VariantKey key = scene.key();
    const std::unique_ptr<Model> model = model_without_gil(scene);
    const ElastoDynShapes shapes = at_spin(omega, [&] {
        const WithoutGil release;
        return elastodyn_mode_shapes(*model, scene.parameters, omega, scene.axial, scene.motion.initial_theta());
    });
    py::dict out;
    out["variant"] = key.name();
    out["omega"] = shapes.omega;
    for (const auto& [file_name, shape] : {std::pair<const char*, const BladeModeShape*>{"BldFl1Sh", &shapes.flap1},
                                           {"BldFl2Sh", &shapes.flap2},
                                           {"BldEdgSh", &shapes.edge1}}) {
        py::dict s;
        s["mode"] = shape->name;
        s["rad_s"] = shape->rad_s;
        s["hz"] = shape->rad_s / (2.0 * M_PI);
        s["coefficients"] = py::array(py::cast(std::vector<double>(shape->fit.coefficients.begin(),
                                                                   shape->fit.coefficients.end())));
        s["residual"] = shape->fit.residual;
        s["xi"] = py::array(py::cast(shape->xi));
        s["phi"] = py::array(py::cast(shape->phi));
        out[file_name] = s;
    }
    out["section"] = elastodyn_section(shapes);
    return out;
}

/// A run's rows saved as hubbeam run writes them, with their metadata (Result.save); ValueError for an output
/// refused before anything is written, OSError for one that could not be written.
/// inputs: the files the rows came from, (path, name) as run() gives them, which the outputs may not be.
void save(const std::string& path, const py::array_t<double, py::array::c_style | py::array::forcecast>& data,
          const std::string& header, const std::string& metadata,
          const std::vector<std::pair<std::string, std::string>>& inputs)
{
    if (data.ndim() != 2) throw py::value_error("data: expected a rows x columns array");
    std::vector<NamedPath> named;
    for (const auto& [file, name] : inputs) named.push_back({file, name});
    std::string why;
    try {
        why = save_rows(path, data.data(), static_cast<std::size_t>(data.shape(0)),
                        static_cast<std::size_t>(data.shape(1)), header, metadata, named);
    } catch (const OutputRefused& e) {
        throw py::value_error(e.what());
    }
    if (!why.empty()) {
        PyErr_SetString(PyExc_OSError, why.c_str());
        throw py::error_already_set();
    }
}

/// The effective scene as TOML: every key, defaults filled, the keywords applied (hubbeam.effective_scene).
std::string effective_scene_text(const std::string& text, const std::string& name, const Keywords& keywords)
{
    return effective_scene_toml(scene_of(text, name, keywords));
}

/// Every scene key with what it takes, its kind ("number", "integer", "word", "text" or "file": the name of a file
/// the scene reads) and, for a file, the most bytes the core reads of it (0 otherwise): the keyword arguments, and
/// the one list of a scene's file keys that Result.save and the sweeps use.
std::vector<std::tuple<std::string, std::string, std::string, std::size_t>> keys()
{
    std::vector<std::tuple<std::string, std::string, std::string, std::size_t>> out;
    for (const SceneKey& k : scene_keys()) {
        using K = SceneKey::Kind;
        const char* kind = k.kind == K::number    ? "number"
                           : k.kind == K::integer ? "integer"
                           : k.kind == K::word    ? "word"
                           : k.kind == K::file    ? "file"
                                                  : "text";
        out.emplace_back(k.name, k.expected, kind, k.max_bytes);
    }
    return out;
}

/// The files the scene text `text` (the file `name`'s) names with the keywords' keys set, as (file key, path)
/// (scene.hpp's scene_files): what a sweep's point reads, even where the point is refused for another key.
std::vector<std::pair<std::string, std::string>> files_of(const std::string& text, const std::string& name,
                                                          const Keywords& keywords)
{
    Overrides overrides;
    for (const auto& [key, value, keyword] : keywords) overrides.emplace_back(key, value);
    try {
        return scene_files(text, name, overrides);
    } catch (const SceneError& e) {
        const std::string keyword = keyword_of(keywords, e.key);
        throw py::value_error(keyword.empty() ? e.what() : keyword + ": " + e.problem());
    }
}

}  // namespace

PYBIND11_MODULE(_core, m)
{
    m.doc() = "hubbeam's C++ core: use the functions of the hubbeam package instead";
    m.def("run", &run, "Runs a scene given as TOML text; returns the rows and the summary", py::arg("text"),
          py::arg("name"), py::arg("overrides"), py::arg("cancellable") = false, py::arg("torque") = py::none(),
          py::arg("sensitivities") = py::none());
    m.def(
        "cancel_runs", [] { ++cancel_generation; }, "Stops every cancellable run in progress in this process");
    m.def(
        "interrupt_runs", [] { exiting = true; },
        "Stops every run and modes computation of this process, now and later, with KeyboardInterrupt");
    m.def("modes", &modes, "Every mode of a scene's variant at each spin rate", py::arg("text"), py::arg("name"),
          py::arg("overrides"), py::arg("omegas"), py::arg("harmonics"), py::arg("cancellable") = false,
          py::arg("frame") = "");
    m.def("linearize", &linearize, "State-space matrices about a steady spin", py::arg("text"), py::arg("name"),
          py::arg("overrides"), py::arg("omega"), py::arg("frame") = "");
    m.def("elastodyn_mode_shapes", &elastodyn_shapes, "A blade's mode shapes and their ElastoDyn polynomials",
          py::arg("text"), py::arg("name"), py::arg("overrides"), py::arg("omega"));
    m.def(
        "check", [](const std::string& text, const std::string& name) { scene_of(text, name, {}); },
        "Parses and checks a scene (ValueError if it is bad)", py::arg("text"), py::arg("name"));
    m.def("save_rows", &save, "Writes a run's rows and metadata as hubbeam run does", py::arg("path"), py::arg("data"),
          py::arg("header"), py::arg("metadata"), py::arg("inputs"));
    m.def(
        "unsafe_character", [](const py::bytes& text) { return unsafe_character(std::string(text)); },
        "Why a name may not be an output's or be handed to another program (its first control or format character, "
        "or byte that is not UTF-8), or an empty string: the one check every writer makes",
        py::arg("text"));
    m.def("scene_files", &files_of, "The files a scene names, by file key", py::arg("text"), py::arg("name"),
          py::arg("overrides"));
    m.def("effective_scene", &effective_scene_text, "The effective scene as TOML", py::arg("text"), py::arg("name"),
          py::arg("overrides"));
    m.def("scene_keys", &keys, "Every scene key (dotted name), what it takes, its kind and a file's byte limit");
    m.def(
        "generator_version", [] { return generator_version(); },
        "The generator's version: on-demand variants are cached under it");
    m.attr("__version__") = HUBBEAM_VERSION;
}
