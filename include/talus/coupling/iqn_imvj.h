#ifndef talus_coupling_iqn_imvj_h
#define talus_coupling_iqn_imvj_h

#include <talus/coupling/accelerators.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deque>
#include <string>

namespace Talus
{
  namespace Coupling
  {
    /**
     * Interface quasi-Newton with an inverse Jacobian carried from window to
     * window, IQN-IMVJ, the "multi-vector" update (Degroote & Vierendeels
     * 2011, Comput. Methods Appl. Mech. Engrg. 200:2195-2210; Bogaers, Kok,
     * Reddy & Franz 2014, Comput. Methods Appl. Mech. Engrg. 279:113-132,
     * "MVQN"; Lindner,
     * Mehl, Uekermann & Bungartz 2015, "A comparison of various quasi-Newton
     * schemes for partitioned fluid-structure interaction", Proc. ECCOMAS
     * Coupled Problems; preCICE's MVQNAcceleration without restart).
     *
     * With V = [Δr_i], W = [Δx̃_i] the differences of this window only
     * (newest first, filtered and factorised V = QR as in IQNILS, at most
     * `IQN-ILS maximum columns`) and J_prev the n × n inverse Jacobian
     * (Δx̃ ≈ J Δr) of the previous windows (0 in the first window), the
     * window's approximation is the least-change update
     * @f[ J_k = J_{prev} + (W - J_{prev} V)(V^T V)^{-1} V^T
     *         = J_{prev} + (W - J_{prev} V) R^{-1} Q^T @f]
     * and the step is x_{k+1} = x̃_k − J_k r_k, evaluated without forming
     * J_k as
     * @f[ x_{k+1} = \tilde x_k + W c - J_{prev} (r_k + V c), \qquad
     *     R c = -Q^T r_k, @f]
     * i.e. the IQN-ILS step plus J_prev applied to the part of r_k the
     * window's columns do not explain. At the end of a window (with the
     * converged pair's column) J_prev ← J_k, formed explicitly with
     * dealii::FullMatrix products (O(n² m) per window, m columns; O(n²) per
     * iteration), and the columns are cleared: no column reuse, the past is
     * in J_prev. In the first window J_prev = 0 and the steps are those of
     * IQN-ILS without reuse; the first iteration of the first window (and
     * after reset()) relaxes with ω_0, the first iteration of a later window
     * is x_1 = x̃_0 − J_prev r_0. For a linear operator x̃ = A x + b the
     * exact inverse Jacobian is A (A − I)^{-1}, independent of b.
     *
     * Filters, round-off guards, the stagnation guard and the fall-back
     * relaxation (no columns and no J_prev) are those of IQNILS.
     *
     * Memory: J_prev has n² doubles on every rank (the interface vectors are
     * replicated). No restart variant (RS-0, RS-SVD of Scheufele & Mehl
     * 2017): instead interfaces with more than @p maximum_dofs DoFs are
     * rejected with an exception at the first step. J_prev is part of a
     * checkpoint of a coupled run (save(), load()), as are the IQN-ILS
     * columns: a resumed run continues as the uninterrupted one.
     */
    class IQNIMVJ : public InterfaceAccelerator
    {
    public:
      /** Largest interface (n² doubles = 200 MB per rank). */
      static constexpr unsigned int default_maximum_dofs = 5000;

      /**
       * @p initial_relaxation ω_0 in (0, 1], @p maximum_columns >= 1 per
       * window, @p filter with tolerance @p filter_tolerance > 0, at most
       * @p maximum_dofs interface DoFs.
       */
      IQNIMVJ(const double         initial_relaxation,
              const unsigned int   maximum_columns,
              const IQNILS::Filter filter,
              const double         filter_tolerance,
              const unsigned int   maximum_dofs = default_maximum_dofs);

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

      /** Also forgets J_prev. */
      void
      reset() override;

      /** Columns of the current window. */
      unsigned int
      n_columns() const;

      /** Columns removed by the filter (or the round-off guard) since the
       * last reset(). */
      unsigned int
      n_filtered_columns() const;

      /** Whether J_prev exists (a window converged since the last reset()
       * with at least one column). */
      bool
      has_inverse_jacobian() const;

      /** J_prev, the inverse Jacobian of the windows so far (Δx̃ ≈ J Δr);
       * empty without one. */
      const dealii::FullMatrix<double> &
      inverse_jacobian() const;

      /** J_prev, the columns of this window and the iteration state (a
       * checkpoint). */
      void
      save(boost::archive::binary_oarchive &archive) const override;

      void
      load(boost::archive::binary_iarchive &archive) override;

    private:
      /** One column of V and W. */
      struct Column
      {
        dealii::Vector<double> delta_residual;
        dealii::Vector<double> delta_x_tilde;
      };

      /** As IQNILS::add_differences(). */
      void
      add_differences(const dealii::Vector<double> &residual,
                      const dealii::Vector<double> &x_tilde);

      /** The oldest columns beyond the maximum (and beyond n without a
       * filter). */
      void
      drop_old_columns();

      /** Stop with a clear message if @p n exceeds the maximum. */
      void
      check_size(const unsigned int n) const;

      const double         omega_initial;
      const unsigned int   maximum_columns;
      const IQNILS::Filter filter;
      const double         filter_tolerance;
      const unsigned int   maximum_dofs;

      std::deque<Column>         columns; // newest first, this window
      dealii::FullMatrix<double> jacobian;
      bool                       have_jacobian = false;
      dealii::Vector<double>     previous_residual;
      dealii::Vector<double>     previous_x_tilde;
      bool                       have_previous  = false;
      bool                       stagnated      = false;
      unsigned int               filtered_total = 0;
    };
  } // namespace Coupling
} // namespace Talus

#endif
