// The stepper families behind Stepper: GSL odeiv2's evolve/driver pair, and SUNDIALS CVODES's variable-order BDF
// with Newton iterations whose matrix is factored rarely and reused across steps (and its staggered sensitivities).
#include "dynamics/stepper.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <cvodes/cvodes.h>
#include <gsl/gsl_errno.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace hubbeam {

namespace {

/// GSL's error handler off while any GSL stepper lives (GSL's default aborts the process; odeiv2 failures must come
/// back as statuses), the caller's handler restored when the last one ends. The handler is one per process: runs on
/// several threads count their steppers under a lock, so that none restores the handler while another still steps
/// (a handler swapped per run would be restored under the other run, and its next GSL error abort the process).
class QuietGsl {
public:
    QuietGsl()
    {
        const std::lock_guard guard(mutex_);
        if (users_++ == 0) previous_ = gsl_set_error_handler_off();
    }
    ~QuietGsl()
    {
        const std::lock_guard guard(mutex_);
        if (--users_ == 0) gsl_set_error_handler(previous_);
    }
    QuietGsl(const QuietGsl&) = delete;
    QuietGsl& operator=(const QuietGsl&) = delete;

private:
    static inline std::mutex mutex_;
    static inline int users_ = 0;
    static inline gsl_error_handler_t* previous_ = nullptr;
};

/// A GSL step-size control that applies another (GSL's own, on y) to the leading entries of y only: the error of the
/// others never shortens a step, in GSL's error test (hadjust) as in its multistep steppers' (errlevel, infinite
/// for them). The state's steps are then exactly those of a run without the trailing entries.
struct LeadingControl {
    gsl_odeiv2_control* inner = nullptr;
    std::size_t controlled = 0;

    static void* alloc() { return new LeadingControl; }
    static int init(void* s, double eps_abs, double eps_rel, double a_y, double a_dydt)
    {
        return gsl_odeiv2_control_init(self(s).inner, eps_abs, eps_rel, a_y, a_dydt);
    }
    static int hadjust(void* s, std::size_t, unsigned int order, const double y[], const double yerr[],
                       const double yp[], double* h)
    {
        const gsl_odeiv2_control& c = *self(s).inner;
        return c.type->hadjust(c.state, self(s).controlled, order, y, yerr, yp, h);
    }
    static int errlevel(void* s, double y, double dydt, double h, std::size_t i, double* level)
    {
        if (i >= self(s).controlled) {
            *level = INFINITY;
            return GSL_SUCCESS;
        }
        return gsl_odeiv2_control_errlevel(self(s).inner, y, dydt, h, i, level);
    }
    static int set_driver(void* s, const gsl_odeiv2_driver* d)
    {
        return gsl_odeiv2_control_set_driver(self(s).inner, d);
    }
    static void free(void* s)
    {
        gsl_odeiv2_control_free(self(s).inner);
        delete &self(s);
    }
    static LeadingControl& self(void* s) { return *static_cast<LeadingControl*>(s); }
    static inline const gsl_odeiv2_control_type type = {"leading", alloc, init, hadjust, errlevel, set_driver, free};
};

/// GSL's driver: evolve_apply for one step at a time, driver_apply to reach a time exactly.
class GslStepper final : public Stepper {
public:
    GslStepper(FirstOrderSystem& system, const gsl_odeiv2_step_type* type, double h0, double atol, double rtol)
        : system_(system), driver_(make_driver(system, type, h0, atol, rtol)), h_(h0), h0_(h0)
    {
        if (driver_ == nullptr) throw std::runtime_error(std::string("GSL could not allocate the ") + type->name + " driver");
    }
    ~GslStepper() override { gsl_odeiv2_driver_free(driver_); }
    GslStepper(const GslStepper&) = delete;
    GslStepper& operator=(const GslStepper&) = delete;

    StepStatus step(double& t, double target, double* y, double h_max) override
    {
        h_ = std::min(h_, h_max);
        return from_gsl(gsl_odeiv2_evolve_apply(driver_->e, driver_->c, driver_->s, system_.gsl(), &t, target, &h_, y));
    }
    StepStatus advance(double& t, double t1, double* y) override
    {
        return from_gsl(gsl_odeiv2_driver_apply(driver_, &t, t1, y));
    }
    void restart(double t, const double* y) override
    {
        retake(t, y);
        h_ = std::min(h_, h0_);
    }
    void retake(double, const double*) override
    {
        past_ += static_cast<long>(driver_->e->count);
        past_rejected_ += static_cast<long>(driver_->e->failed_steps);
        gsl_odeiv2_driver_reset(driver_);
    }
    long steps() const override { return past_ + static_cast<long>(driver_->e->count); }
    // evolve_apply counts a step its control shortened and took again (an error test failed) in failed_steps.
    long rejected() const override { return past_rejected_ + static_cast<long>(driver_->e->failed_steps); }

private:
    /// GSL's driver with the control on y (atol + rtol |y_i|), restricted to the leading entries the system's error
    /// control weighs (controlled_size, LeadingControl).
    static gsl_odeiv2_driver* make_driver(FirstOrderSystem& system, const gsl_odeiv2_step_type* type, double h0,
                                          double atol, double rtol)
    {
        gsl_odeiv2_driver* d = gsl_odeiv2_driver_alloc_y_new(system.gsl(), type, h0, atol, rtol);
        if (d != nullptr && system.controlled_size() < system.size()) {
            gsl_odeiv2_control* leading = gsl_odeiv2_control_alloc(&LeadingControl::type);
            auto* state = static_cast<LeadingControl*>(leading->state);
            state->inner = d->c;
            state->controlled = static_cast<std::size_t>(system.controlled_size());
            d->c = leading;
        }
        return d;
    }

    const QuietGsl quiet_;  // first: GSL's own allocations may report an error too
    FirstOrderSystem& system_;
    gsl_odeiv2_driver* driver_;
    double h_, h0_;
    long past_ = 0, past_rejected_ = 0;  // before the last restart (GSL's counts start again at a reset)
};

/// CVODE's BDF (orders 1 to 5) with Newton iterations on a dense matrix I - gamma J. CVODE forms the Jacobian J from
/// the system's (exact where the model has derivatives) only when its Newton iteration converges slowly or every
/// 51 steps, and refactors I - gamma J when gamma changes by more than 30 % or every 20 steps: on the hub-beam's
/// equations, linear in (q, qd) once a prescribed drive is steady, most steps reuse both. A system with sensitivity
/// blocks (FirstOrderSystem::blocks) integrates them by CVODES's staggered corrector: the state's Newton iteration
/// converged first, then the sensitivities', linear, with the state's matrix, as gauss4 does; they are left out of
/// the error test where the system leaves them out of its control (errconS).
class CvodeStepper final : public Stepper {
public:
    CvodeStepper(FirstOrderSystem& system, double t0, const double* y0, double h0, double atol, double rtol)
        : system_(system),
          n_(system.size()),
          state_(n_ / system.blocks()),
          count_(system.blocks() - 1),
          dfdy_(static_cast<std::size_t>(state_) * state_),
          dfdt_(static_cast<std::size_t>(state_))
    {
        if (SUNContext_Create(nullptr, &context_) != 0) throw std::runtime_error("SUNDIALS could not create a context");
        y_ = N_VNew_Serial(state_, context_);
        matrix_ = SUNDenseMatrix(state_, state_, context_);
        mem_ = CVodeCreate(CV_BDF, context_);
        if (y_ == nullptr || matrix_ == nullptr || mem_ == nullptr) throw std::runtime_error("CVODE could not allocate");
        solver_ = SUNLinSol_Dense(y_, matrix_, context_);
        std::copy_n(y0, state_, N_VGetArrayPointer(y_));
        const bool ok = CVodeSetErrHandlerFn(mem_, quiet, nullptr) == CV_SUCCESS &&
                        CVodeInit(mem_, rhs, t0, y_) == CV_SUCCESS && CVodeSetUserData(mem_, this) == CV_SUCCESS &&
                        CVodeSStolerances(mem_, rtol, atol) == CV_SUCCESS &&
                        CVodeSetLinearSolver(mem_, solver_, matrix_) == CV_SUCCESS &&
                        CVodeSetJacFn(mem_, jacobian) == CV_SUCCESS && CVodeSetInitStep(mem_, h0) == CV_SUCCESS &&
                        CVodeSetMaxNumSteps(mem_, -1) == CV_SUCCESS &&
                        (count_ == 0 || init_sensitivities(y0, rtol, atol));
        if (!ok) throw std::runtime_error("CVODE could not be set up");
    }
    /// The sensitivity blocks of y0 as CVODES's staggered sensitivities, under the state's tolerances (the system
    /// scales them to the state's units), in the error test where the system controls them.
    bool init_sensitivities(const double* y0, double rtol, double atol)
    {
        sensitivities_ = N_VCloneVectorArray(count_, y_);
        if (sensitivities_ == nullptr) return false;
        scratch_.resize(static_cast<std::size_t>(n_));
        rates_.resize(static_cast<std::size_t>(n_));
        blocks_to_vectors(y0, sensitivities_);
        std::vector<double> atols(static_cast<std::size_t>(count_), atol);
        return CVodeSensInit(mem_, count_, CV_STAGGERED, sensitivity_rhs, sensitivities_) == CV_SUCCESS &&
               CVodeSensSStolerances(mem_, rtol, atols.data()) == CV_SUCCESS &&
               CVodeSetSensErrCon(mem_, system_.controlled_size() == n_ ? SUNTRUE : SUNFALSE) == CV_SUCCESS;
    }
    ~CvodeStepper() override
    {
        if (sensitivities_ != nullptr) N_VDestroyVectorArray(sensitivities_, count_);
        CVodeFree(&mem_);
        SUNLinSolFree(solver_);
        SUNMatDestroy(matrix_);
        N_VDestroy(y_);
        SUNContext_Free(&context_);
    }
    CvodeStepper(const CvodeStepper&) = delete;
    CvodeStepper& operator=(const CvodeStepper&) = delete;

    StepStatus step(double& t, double target, double* y, double h_max) override
    {
        if (h_max != h_max_) {
            CVodeSetMaxStep(mem_, std::isfinite(h_max) ? h_max : 0.0);  // 0: no limit
            h_max_ = h_max;
        }
        return solve(t, target, y, CV_ONE_STEP);
    }
    StepStatus advance(double& t, double t1, double* y) override { return solve(t, t1, y, CV_NORMAL); }
    void restart(double t, const double* y) override
    {
        past_ = steps();
        past_rejected_ = rejected();
        std::copy_n(y, state_, N_VGetArrayPointer(y_));
        CVodeReInit(mem_, t, y_);
        if (sensitivities_ != nullptr) {
            blocks_to_vectors(y, sensitivities_);
            CVodeSensReInit(mem_, CV_STAGGERED, sensitivities_);
        }
    }
    void retake(double t, const double* y) override { restart(t, y); }
    long steps() const override
    {
        long n = 0;
        CVodeGetNumSteps(mem_, &n);
        return past_ + n;
    }
    long rejected() const override
    {
        long n = 0;
        CVodeGetNumErrTestFails(mem_, &n);
        return past_rejected_ + n;
    }

private:
    StepStatus solve(double& t, double target, double* y, int task)
    {
        CVodeSetStopTime(mem_, target);
        double reached = t;
        const int flag = CVode(mem_, target, y_, &reached, task);
        if (flag < 0) return from_gsl(status(flag));
        t = reached;
        std::copy_n(N_VGetArrayPointer(y_), state_, y);
        if (sensitivities_ != nullptr) {
            if (CVodeGetSens(mem_, &reached, sensitivities_) != CV_SUCCESS) return from_gsl(GSL_FAILURE);
            vectors_to_blocks(sensitivities_, y);
        }
        return StepStatus::success;
    }

    /// A whole y's sensitivity blocks (those after the state's) into CVODES's vectors, and back.
    void blocks_to_vectors(const double* y, N_Vector* vectors) const
    {
        for (int j = 0; j < count_; ++j)
            std::copy_n(y + static_cast<std::ptrdiff_t>(j + 1) * state_, state_, N_VGetArrayPointer(vectors[j]));
    }
    void vectors_to_blocks(N_Vector* vectors, double* y) const
    {
        for (int j = 0; j < count_; ++j)
            std::copy_n(N_VGetArrayPointer(vectors[j]), state_, y + static_cast<std::ptrdiff_t>(j + 1) * state_);
    }

    /// CVODE's failures as the GSL statuses of their kind, so that a failure's message reads alike in every family.
    static int status(int flag)
    {
        switch (flag) {
        case CV_RHSFUNC_FAIL:
        case CV_FIRST_RHSFUNC_ERR:
        case CV_REPTD_RHSFUNC_ERR:
        case CV_UNREC_RHSFUNC_ERR:
        case CV_LSETUP_FAIL: return GSL_EBADFUNC;
        case CV_CONV_FAILURE: return GSL_EMAXITER;
        default: return GSL_FAILURE;
        }
    }

    // A right-hand side that fails (M not positive definite at a trial state) is recoverable: CVODE retries with
    // a shorter step, and reports it as repeated when that does not help.
    static int rhs(double t, N_Vector y, N_Vector ydot, void* self)
    {
        auto& s = *static_cast<CvodeStepper*>(self);
        const int status = s.sensitivities_ != nullptr
                               ? s.system_.FirstOrderSystem::rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot))
                               : s.system_.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
        return status == GSL_SUCCESS ? 0 : 1;
    }
    /// Every sensitivity's rate at once, from the system's right-hand side of the whole y (the state's and the
    /// sensitivities' together).
    static int sensitivity_rhs(int, double t, N_Vector y, N_Vector, N_Vector* sensitivities, N_Vector* rates,
                               void* self, N_Vector, N_Vector)
    {
        auto& s = *static_cast<CvodeStepper*>(self);
        std::copy_n(N_VGetArrayPointer(y), s.state_, s.scratch_.data());
        s.vectors_to_blocks(sensitivities, s.scratch_.data());
        if (s.system_.rhs(t, s.scratch_.data(), s.rates_.data()) != GSL_SUCCESS) return 1;
        s.blocks_to_vectors(s.rates_.data(), rates);
        return 0;
    }
    static int jacobian(double t, N_Vector y, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector)
    {
        auto& s = *static_cast<CvodeStepper*>(self);
        const int status = s.sensitivities_ != nullptr
                               ? s.system_.FirstOrderSystem::jacobian(t, N_VGetArrayPointer(y), s.dfdy_.data(),
                                                                      s.dfdt_.data())
                               : s.system_.jacobian(t, N_VGetArrayPointer(y), s.dfdy_.data(), s.dfdt_.data());
        if (status != GSL_SUCCESS) return 1;
        const int n = s.state_;
        double* column_major = SUNDenseMatrix_Data(J);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) column_major[j * n + i] = s.dfdy_[static_cast<std::size_t>(i * n + j)];
        return 0;
    }
    static void quiet(int, const char*, const char*, char*, void*) {}  // failures come back as statuses

    FirstOrderSystem& system_;
    int n_, state_, count_;            // y's size, its state's (y without sensitivity blocks), the sensitivity blocks
    std::vector<double> dfdy_, dfdt_;  // the state's row-major Jacobian, before it is copied column-major
    N_Vector* sensitivities_ = nullptr;
    std::vector<double> scratch_, rates_;  // a whole y and its rates, for the sensitivities' right-hand side
    SUNContext context_ = nullptr;
    N_Vector y_ = nullptr;
    SUNMatrix matrix_ = nullptr;
    SUNLinearSolver solver_ = nullptr;
    void* mem_ = nullptr;
    double h_max_ = INFINITY;
    long past_ = 0, past_rejected_ = 0;  // before the last restart (CVODE's counts start again at a re-initialisation)
};

}  // namespace

StepStatus Stepper::from_gsl(int status)
{
    if (status == GSL_SUCCESS) return StepStatus::success;
    StepStatus kind = StepStatus::other;
    switch (status) {
    case GSL_EBADFUNC: kind = StepStatus::equations_failed; break;
    case GSL_FAILURE: kind = StepStatus::no_step; break;
    case GSL_ENOPROG: kind = StepStatus::no_progress; break;
    case GSL_EMAXITER: kind = StepStatus::not_converged; break;
    default: break;
    }
    failure_ = {"GSL status " + std::to_string(status), kind == StepStatus::other ? gsl_strerror(status) : ""};
    return kind;
}

std::unique_ptr<Stepper> make_stepper(FirstOrderSystem& system, const std::string& stepper, double t0, const double* y0,
                                      double h0, double atol, double rtol)
{
    if (stepper == gauss_stepper) return make_gauss_stepper(system, h0, atol, rtol);
    if (stepper == cvode_stepper) return std::make_unique<CvodeStepper>(system, t0, y0, h0, atol, rtol);
    const gsl_odeiv2_step_type* type = step_type(stepper);
    if (type == nullptr) throw std::invalid_argument("unknown stepper '" + stepper + "'");
    return std::make_unique<GslStepper>(system, type, h0, atol, rtol);
}

}  // namespace hubbeam
