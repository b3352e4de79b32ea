#include <talus/coupling/iqn_imvj.h>

#include <deal.II/base/exceptions.h>

#include <deal.II/lac/qr.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "qr_filter.h"

namespace Talus
{
  namespace Coupling
  {
    IQNIMVJ::IQNIMVJ(const double         initial_relaxation,
                     const unsigned int   maximum_columns,
                     const IQNILS::Filter filter,
                     const double         filter_tolerance,
                     const unsigned int   maximum_dofs)
      : omega_initial(initial_relaxation)
      , maximum_columns(std::max(1U, maximum_columns))
      , filter(filter)
      , filter_tolerance(filter_tolerance)
      , maximum_dofs(maximum_dofs)
    {}


    std::string
    IQNIMVJ::name() const
    {
      return "IQN-IMVJ";
    }


    void
    IQNIMVJ::check_size(const unsigned int n) const
    {
      AssertThrow(
        n <= maximum_dofs,
        dealii::ExcMessage(
          "IQN-IMVJ keeps an explicit n x n inverse Jacobian on every rank, "
          "but the interface has n = " +
          std::to_string(n) + " DoFs, more than the limit of " +
          std::to_string(maximum_dofs) + " (" +
          std::to_string(8. * maximum_dofs * maximum_dofs / 1e6) +
          " MB); there is no restart variant (doc/coupling.md). Use "
          "'set acceleration = IQN-ILS' (with 'IQN-ILS reuse') for this "
          "interface."));
    }


    void
    IQNIMVJ::start_window()
    {
      InterfaceAccelerator::start_window();
      columns.clear();
      have_previous = false;
      stagnated     = false;
    }


    void
    IQNIMVJ::add_differences(const dealii::Vector<double> &residual,
                             const dealii::Vector<double> &x_tilde)
    {
      if (have_previous)
        {
          Column column{residual, x_tilde};
          column.delta_residual -= previous_residual;
          column.delta_x_tilde -= previous_x_tilde;
          const double residual_norm = residual.l2_norm();
          const double difference    = column.delta_residual.l2_norm();
          stagnated                  = residual_norm > 0. &&
                      difference <= internal::stagnation_ratio * residual_norm;
          if (difference >
              internal::roundoff_difference *
                std::max(residual_norm, previous_residual.l2_norm()))
            columns.push_front(std::move(column));
          else
            ++filtered_total;
        }
      previous_residual = residual;
      previous_x_tilde  = x_tilde;
      have_previous     = true;
    }


    void
    IQNIMVJ::drop_old_columns()
    {
      // Without a filter, at most n columns (preCICE's 'overdetermined'
      // rule, as IQNILS).
      const std::size_t rows =
        (filter == IQNILS::Filter::none && !columns.empty() ?
           columns.front().delta_residual.size() :
           maximum_columns);
      while (columns.size() > std::min<std::size_t>(maximum_columns, rows))
        columns.pop_back();
    }


    dealii::Vector<double>
    IQNIMVJ::compute_next(const dealii::Vector<double> &x,
                          const dealii::Vector<double> &x_tilde)
    {
      check_size(x.size());
      if (have_jacobian && jacobian.m() != x.size())
        have_jacobian = false; // the interface changed: start anew
      dealii::Vector<double> residual(x_tilde);
      residual -= x;
      add_differences(residual, x_tilde);
      drop_old_columns();

      last_info             = AccelerationInfo();
      const bool first_step = (!have_jacobian && window_iteration == 0);
      ++window_iteration;

      dealii::QR<dealii::Vector<double>> qr;
      std::vector<unsigned int>          kept;
      unsigned int                       removed = 0;
      if (!first_step && !stagnated)
        {
          removed = internal::filter_columns(
            columns, filter, filter_tolerance, qr, kept);
          filtered_total += removed;
        }
      last_info.filtered_columns = removed;

      dealii::Vector<double> next(x);
      if (first_step || stagnated || (qr.size() == 0 && !have_jacobian))
        {
          next.add(omega_initial, residual);
          last_info.relaxation = omega_initial;
          last_info.fallback   = !first_step;
          stagnated            = false;
          return next;
        }

      // x_{k+1} = x̃_k + W c − J_prev (r_k + V c), R c = −Qᵀ r_k.
      next = x_tilde;
      dealii::Vector<double> unexplained(residual);
      if (qr.size() > 0)
        {
          dealii::Vector<double> qt_r(qr.size());
          qr.multiply_with_QT(qt_r, residual);
          dealii::Vector<double> c(qr.size());
          qr.solve(c, qt_r); // c = −(the c above)
          for (unsigned int j = 0; j < kept.size(); ++j)
            {
              next.add(-c[j], columns[kept[j]].delta_x_tilde);
              unexplained.add(-c[j], columns[kept[j]].delta_residual);
            }
        }
      if (have_jacobian)
        {
          dealii::Vector<double> j_r(x.size());
          jacobian.vmult(j_r, unexplained);
          next -= j_r;
        }
      last_info.quasi_newton = true;
      last_info.columns      = qr.size();
      return next;
    }


    void
    IQNIMVJ::end_window(const dealii::Vector<double> &x,
                        const dealii::Vector<double> &x_tilde)
    {
      check_size(x.size());
      if (have_jacobian && jacobian.m() != x.size())
        have_jacobian = false;
      dealii::Vector<double> residual(x_tilde);
      residual -= x;
      add_differences(residual, x_tilde);
      drop_old_columns();

      dealii::QR<dealii::Vector<double>>          qr;
      std::vector<unsigned int>                   kept;
      std::vector<const dealii::Vector<double> *> v;
      for (const Column &column : columns)
        v.push_back(&column.delta_residual);
      filtered_total +=
        internal::build_filtered_qr(v, filter, filter_tolerance, qr, kept);

      const unsigned int n = x.size();
      const unsigned int m = qr.size();
      if (m > 0)
        {
          if (!have_jacobian)
            jacobian.reinit(n, n); // zero
          // J ← J + (W − J V) R⁻¹ Qᵀ, as (W̃ R⁻¹) Qᵀ.
          dealii::FullMatrix<double> W_tilde(n, m), Q(n, m), R_inverse(m, m);
          dealii::Vector<double>     w(n), jv(n), q(n), e(m), r_column(m);
          for (unsigned int j = 0; j < m; ++j)
            {
              w = columns[kept[j]].delta_x_tilde;
              if (have_jacobian)
                {
                  jacobian.vmult(jv, columns[kept[j]].delta_residual);
                  w -= jv;
                }
              e    = 0.;
              e[j] = 1.;
              qr.multiply_with_Q(q, e);
              qr.solve(r_column, e);
              for (unsigned int i = 0; i < n; ++i)
                {
                  W_tilde(i, j) = w[i];
                  Q(i, j)       = q[i];
                }
              for (unsigned int i = 0; i < m; ++i)
                R_inverse(i, j) = r_column[i];
            }
          dealii::FullMatrix<double> A(n, m);
          W_tilde.mmult(A, R_inverse);
          A.mTmult(jacobian, Q, true);
          have_jacobian = true;
        }
      columns.clear();
      have_previous = false;
      stagnated     = false;
    }


    void
    IQNIMVJ::reset()
    {
      InterfaceAccelerator::reset();
      columns.clear();
      jacobian.reinit(0, 0);
      have_jacobian  = false;
      have_previous  = false;
      stagnated      = false;
      filtered_total = 0;
    }


    unsigned int
    IQNIMVJ::n_columns() const
    {
      return columns.size();
    }


    unsigned int
    IQNIMVJ::n_filtered_columns() const
    {
      return filtered_total;
    }


    bool
    IQNIMVJ::has_inverse_jacobian() const
    {
      return have_jacobian;
    }


    const dealii::FullMatrix<double> &
    IQNIMVJ::inverse_jacobian() const
    {
      return jacobian;
    }
  } // namespace Coupling
} // namespace Talus
