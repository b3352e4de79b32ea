#ifndef talus_coupling_accelerators_h
#define talus_coupling_accelerators_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/vector.h>

#include <deque>
#include <functional>
#include <memory>
#include <string>

namespace boost
{
  namespace archive
  {
    class binary_oarchive;
    class binary_iarchive;
  } // namespace archive
} // namespace boost

namespace Talus
{
  /**
   * The partitioned Dirichlet-Neumann coupling of the MPM soil and the
   * barrier structure (doc/coupling.md). Everything here works on interface
   * vectors: the displacement of the structure's interface DoFs, a
   * dealii::Vector<double> replicated on every rank, so that all ranks take
   * the same decisions without communication.
   */
  namespace Coupling
  {
    /**
     * What an accelerator did in its last call of
     * InterfaceAccelerator::compute_next(), for the coupled step's log.
     */
    struct AccelerationInfo
    {
      /** Relaxation factor ω of a relaxation step x + ω r (constant,
       * Aitken, or the relaxation step of IQN-ILS); 0 for a
       * quasi-Newton step. */
      double relaxation = 0.;

      /** IQN-ILS, IQN-IMVJ: the step came from the quasi-Newton model. */
      bool quasi_newton = false;

      /** IQN-ILS, IQN-IMVJ: columns of the least-squares model used in
       * this step. */
      unsigned int columns = 0;

      /** IQN-ILS, IQN-IMVJ: columns removed in this step by the QR filter (or
       * because they are zero or dependent to round-off). */
      unsigned int filtered_columns = 0;

      /** No secant or column information was available (zero residual
       * difference, a residual following a zero one, every column filtered
       * out): the step fell back to the initial relaxation. */
      bool fallback = false;
    };


    /**
     * A convergence accelerator of the interface fixed-point iteration
     * x̃ = H(x) of one time window (Dirichlet-Neumann Gauss-Seidel: x is the
     * interface displacement handed to the MPM, x̃ the one the structure
     * returns for the MPM's reactions). With the residual r = x̃ − x, each
     * accelerator computes the next iterate x_{k+1} from (x_k, x̃_k) and
     * what it learned in earlier iterations and windows.
     *
     * Call sequence of a coupled step (see iterate_window()):
     * @code
     * accelerator.start_window();
     * for k = 0, 1, ...: x̃_k = H(x_k); if converged: break;
     *                    x_{k+1} = accelerator.compute_next(x_k, x̃_k);
     * accelerator.end_window(x_k, x̃_k);          // converged step
     * accelerator.reset();                       // or: step rejected
     * @endcode
     * end_window() receives the converged pair because its residual
     * difference is the most recent information on the interface Jacobian
     * (preCICE adds it to the IQN model in iterationsConverged()).
     * None of the accelerators divides by a residual or a residual
     * difference without checking that it is nonzero: an interface that
     * carries no force (x = x̃ = 0 before impact) is safe.
     */
    class InterfaceAccelerator
    {
    public:
      virtual ~InterfaceAccelerator() = default;

      /** Name as in the parameter file ("constant", "Aitken", "IQN-ILS",
       * "IQN-IMVJ"). */
      virtual std::string
      name() const = 0;

      /** Begin a new time window (coupled step). */
      virtual void
      start_window();

      /**
       * Next interface displacement x_{k+1} from the current iterate
       * @p x (x_k) and the fixed-point operator's output @p x_tilde (x̃_k).
       */
      virtual dealii::Vector<double>
      compute_next(const dealii::Vector<double> &x,
                   const dealii::Vector<double> &x_tilde) = 0;

      /** The window converged with the pair (@p x, @p x_tilde). */
      virtual void
      end_window(const dealii::Vector<double> &x,
                 const dealii::Vector<double> &x_tilde);

      /**
       * Forget everything learned (step rejected: the repeated step has a
       * different length, so relaxation factors and Jacobian information of
       * the old windows no longer fit). The next window starts like the
       * first one.
       */
      virtual void
      reset();

      /**
       * An initial inverse Jacobian J0 of the residual operator for the
       * current window (Δx̃ ≈ J0 Δr; @p J0 (v, result) sets result =
       * J0 v), set after start_window() and before the window's first
       * compute_next(). Only IQNILS uses one; the others throw.
       */
      virtual void
      set_initial_jacobian(
        const std::function<void(const dealii::Vector<double> &,
                                 dealii::Vector<double> &)> &J0);

      /** What the last compute_next() did. */
      const AccelerationInfo &
      info() const;

      /** Iterations (calls of compute_next()) in the current window. */
      unsigned int
      iteration() const;

      /**
       * Write what the accelerator learned (the history of past windows:
       * relaxation factors, least-squares columns, inverse Jacobian) into
       * a checkpoint archive (doc/checkpoint.md); load() reads it back into
       * an accelerator made from the same parameters, after which it
       * continues bitwise as the one that wrote it.
       */
      virtual void
      save(boost::archive::binary_oarchive &archive) const;

      /** Read the state of save(). */
      virtual void
      load(boost::archive::binary_iarchive &archive);

    protected:
      AccelerationInfo last_info;
      unsigned int     window_iteration = 0;
    };


    /**
     * Constant under-relaxation x_{k+1} = x_k + ω r_k = ω x̃_k + (1 − ω) x_k
     * (preCICE `<relaxation value="ω"/>`). For the linear two-spring
     * Dirichlet-Neumann model with stiffnesses k_D (Dirichlet side, including
     * inertia) and k_N (Neumann side) the error is multiplied by
     * 1 − ω (1 + k_D/k_N) per iteration; ω* = k_N/(k_N + k_D) converges in
     * one update (doc/coupling.md).
     */
    class ConstantRelaxation : public InterfaceAccelerator
    {
    public:
      /** @p relaxation in (0, 1]. */
      explicit ConstantRelaxation(const double relaxation);

      std::string
      name() const override;

      dealii::Vector<double>
      compute_next(const dealii::Vector<double> &x,
                   const dealii::Vector<double> &x_tilde) override;

    private:
      const double omega;
    };


    /**
     * Aitken's dynamic relaxation (Irons & Tuck 1969; for FSI Küttler &
     * Wall 2008, Comput. Mech. 43:61-72; preCICE's AitkenAcceleration):
     * x_{k+1} = x_k + ω_k r_k with
     * @f[ \omega_k = -\omega_{k-1}\,
     *     \frac{r_{k-1}^T (r_k - r_{k-1})}{\|r_k - r_{k-1}\|^2}, @f]
     * a secant of the residual along the last update. In the first
     * iteration of a window ω_0 = sign(ω_prev) min(ω_init, |ω_prev|), ω_prev
     * the last factor of the previous window (ω_init in the first window).
     * On a scalar linear problem the first secant factor is the optimal one,
     * so the window converges after two updates.
     *
     * Robustness: the secant needs r_{k−1} ≠ 0 and a residual difference
     * above round-off, ‖r_k − r_{k−1}‖ > 1e-14 max(‖r_k‖, ‖r_{k−1}‖), and
     * must give a finite nonzero ω; otherwise (no force on the interface
     * yet, a residual appearing after a zero one at impact onset, a
     * stationary residual) the step uses ω_init (AccelerationInfo::fallback).
     * A zero residual leaves x unchanged and ω as it was.
     */
    class AitkenRelaxation : public InterfaceAccelerator
    {
    public:
      /** @p initial_relaxation ω_init in (0, 1]. */
      explicit AitkenRelaxation(const double initial_relaxation);

      std::string
      name() const override;

      void
      start_window() override;

      dealii::Vector<double>
      compute_next(const dealii::Vector<double> &x,
                   const dealii::Vector<double> &x_tilde) override;

      void
      reset() override;

      /** The last relaxation factor used. */
      double
      relaxation() const;

      void
      save(boost::archive::binary_oarchive &archive) const override;

      void
      load(boost::archive::binary_iarchive &archive) override;

    private:
      const double           omega_initial;
      double                 omega;
      dealii::Vector<double> previous_residual;
      bool                   have_previous = false;
    };


    /**
     * Interface quasi-Newton with an approximation of the inverse Jacobian
     * from a least-squares model, IQN-ILS (Degroote, Bathe & Vierendeels
     * 2009, Comput. Struct. 87:793-801; Haelterman et al. 2016, Comput.
     * Struct. 171:9-17 for its equivalence with Anderson acceleration;
     * preCICE's IQNILSAcceleration and BaseQNAcceleration, v3.4).
     *
     * The columns V = [Δr_i], W = [Δx̃_i] hold the differences of successive
     * residuals and operator outputs of this window and of the last q
     * windows (`IQN-ILS reuse`), newest first, at most
     * `IQN-ILS maximum columns` (oldest dropped; without a filter also at
     * most as many as the interface has DoFs, preCICE's 'overdetermined'
     * rule). Each step solves
     * @f[ \min_c \|V c + r_k\|_2 \quad\text{by } V = QR,\;
     *     R c = -Q^T r_k, \qquad x_{k+1} = \tilde x_k + W c @f]
     * with dealii::QR (modified Gram-Schmidt, Givens rotations to remove a
     * column). The first iteration of the first window (no columns yet) is
     * a relaxation step with ω_0 = `initial relaxation`; later windows start
     * with a quasi-Newton step from the reused columns. With q = 0 the
     * previous window's columns still serve the first iteration of the next
     * window and are dropped after it (preCICE's rule).
     *
     * QR filter (preCICE's names), the QR factorisation being rebuilt from
     * the stored columns, newest first, in every step:
     * - QR1: after factorising, remove column i while
     *   |R_ii| < ε ‖R‖_F (and more than one column is left);
     * - QR2: do not append a column whose part orthogonal to the columns
     *   already kept is small, ‖v_⊥‖ < ε ‖v‖;
     * - none: only the round-off guard below.
     * Columns the filter removes are deleted from V and W for good. In all
     * modes a column is never appended if it is zero or
     * ‖v_⊥‖ < 1e-12 ‖v‖ (dependent to round-off: the Gram-Schmidt step would
     * divide by zero), and a residual difference at round-off level is not
     * stored at all. Without any usable column the step is a relaxation
     * step with ω_0 (AccelerationInfo::fallback), so an interface without
     * force never divides by zero.
     *
     * Stagnation guard (not in preCICE): if a step changed a nonzero
     * residual by less than 0.1 %, ‖r_k − r_{k−1}‖ <= 1e-3 ‖r_k‖, the model
     * returned (nearly) the point it had; with the new, tiny column
     * filtered out it would return it for ever (seen with QR1 on the
     * piecewise-linear contact operator of tests/coupling/impact_onset.cc:
     * |Δx| ~ 4e-12 m at |r| ~ 2e-4 m for 25 iterations). The next step is
     * then a relaxation step with ω_0, which moves the iterate and yields
     * an informative column. This turns the stall into progress with QR2
     * and without filter; with QR1 (which measures R_ii against ‖R‖_F and
     * removes the new small columns again) the same test still cycles, so
     * QR1 is not recommended for contact (doc/coupling.md).
     *
     * Not done: residual preconditioning (with one data field, the interface
     * displacement, a scalar weight changes neither c nor the filters).
     * IQNIMVJ (iqn_imvj.h) carries the information of past windows in an
     * explicit inverse Jacobian instead of reused columns.
     */
    class IQNILS : public InterfaceAccelerator
    {
    public:
      /** QR filter of the least-squares columns. */
      enum class Filter
      {
        none,
        QR1,
        QR2
      };

      /**
       * @p initial_relaxation ω_0 in (0, 1], @p reuse q >= 0 windows,
       * @p maximum_columns >= 1, @p filter with tolerance
       * @p filter_tolerance > 0.
       */
      IQNILS(const double       initial_relaxation,
             const unsigned int reuse,
             const unsigned int maximum_columns,
             const Filter       filter,
             const double       filter_tolerance);

      std::string
      name() const override;

      void
      start_window() override;

      dealii::Vector<double>
      compute_next(const dealii::Vector<double> &x,
                   const dealii::Vector<double> &x_tilde) override;

      void
      end_window(const dealii::Vector<double> &x,
                 const dealii::Vector<double> &x_tilde) override;

      void
      reset() override;

      /**
       * With J0 the step is the multi-secant update of J0 (as IQNIMVJ's
       * with J_prev = J0): x_{k+1} = x̃_k − W c − J0 (r_k − V c), and a
       * step without columns (the first of the first window, after a
       * reset() or the stagnation guard) is x̃_k − J0 r_k instead of a
       * relaxation step. The columns of past windows are dropped when J0
       * is set (they are secants of other steps' operators, which the
       * least-change update would bend J0 to fit; J0 is the information
       * carried between windows). Cleared by start_window() (kept by
       * reset()).
       */
      void
      set_initial_jacobian(
        const std::function<void(const dealii::Vector<double> &,
                                 dealii::Vector<double> &)> &J0) override;

      /** Columns stored now (this window and the reused ones). */
      unsigned int
      n_columns() const;

      /** Columns removed by the filter (or the round-off guard) since the
       * last reset(). */
      unsigned int
      n_filtered_columns() const;

      /** The columns V, W of this and the reused windows and the iteration
       * state (a checkpoint). */
      void
      save(boost::archive::binary_oarchive &archive) const override;

      void
      load(boost::archive::binary_iarchive &archive) override;

    private:
      /** One column of V and W and the window it comes from. */
      struct Column
      {
        dealii::Vector<double> delta_residual;
        dealii::Vector<double> delta_x_tilde;
        unsigned int           window;
      };

      /** Store the differences to the last iterate of this window, if any;
       * then remember (r, x̃). */
      void
      add_differences(const dealii::Vector<double> &residual,
                      const dealii::Vector<double> &x_tilde);

      /** Drop columns older than @p max_age windows and the oldest beyond
       * the maximum number. */
      void
      drop_old_columns(const unsigned int max_age);

      const double       omega_initial;
      const unsigned int reuse;
      const unsigned int maximum_columns;
      const Filter       filter;
      const double       filter_tolerance;

      std::function<void(const dealii::Vector<double> &,
                         dealii::Vector<double> &)>
                             initial_jacobian;
      std::deque<Column>     columns; // newest first
      dealii::Vector<double> previous_residual;
      dealii::Vector<double> previous_x_tilde;
      bool                   have_previous    = false;
      bool                   stagnated        = false;
      unsigned int           window           = 0;
      bool                   window_converged = false;
      unsigned int           filtered_total   = 0;
    };


    /**
     * The acceleration parameters of subsection `Coupling`: the method and
     * its settings, declared and parsed here (CouplingParameters calls
     * these inside the subsection).
     */
    struct AccelerationParameters
    {
      enum class Method
      {
        constant,
        Aitken,
        IQN_ILS,
        IQN_IMVJ
      };

      Method         method             = Method::IQN_ILS;
      double         relaxation         = 0.5;
      double         initial_relaxation = 0.1;
      unsigned int   reuse              = 10;
      unsigned int   maximum_columns    = 100;
      IQNILS::Filter filter             = IQNILS::Filter::QR2;
      double         filter_tolerance   = 1e-2;

      /** Declare the entries in the current subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse from the current subsection (@p subsection names it in error
       * messages); out-of-range values throw ExcInvalidInput. */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const std::string        &subsection = "Coupling");
    };


    /** The accelerator @p parameters ask for. */
    std::unique_ptr<InterfaceAccelerator>
    create_accelerator(const AccelerationParameters &parameters);
  } // namespace Coupling
} // namespace Talus

#endif
