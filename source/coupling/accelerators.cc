#include <talus/base/input.h>
#include <talus/coupling/accelerators.h>
#include <talus/coupling/iqn_imvj.h>

#include <deal.II/lac/qr.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "qr_filter.h"
#include "range_checks.h"

namespace Talus
{
  namespace Coupling
  {
    using internal::roundoff_difference;
    using internal::stagnation_ratio;


    // ---------------------------------------------------------------------
    // InterfaceAccelerator

    void
    InterfaceAccelerator::start_window()
    {
      window_iteration = 0;
    }


    void
    InterfaceAccelerator::end_window(const dealii::Vector<double> &,
                                     const dealii::Vector<double> &)
    {}


    void
    InterfaceAccelerator::reset()
    {
      window_iteration = 0;
      last_info        = AccelerationInfo();
    }


    void
    InterfaceAccelerator::set_initial_jacobian(
      const std::function<void(const dealii::Vector<double> &,
                               dealii::Vector<double> &)> &)
    {
      throw std::invalid_argument(
        "an initial Jacobian needs acceleration = IQN-ILS (not " + name() +
        ")");
    }


    const AccelerationInfo &
    InterfaceAccelerator::info() const
    {
      return last_info;
    }


    unsigned int
    InterfaceAccelerator::iteration() const
    {
      return window_iteration;
    }


    // ---------------------------------------------------------------------
    // ConstantRelaxation

    ConstantRelaxation::ConstantRelaxation(const double relaxation)
      : omega(relaxation)
    {}


    std::string
    ConstantRelaxation::name() const
    {
      return "constant";
    }


    dealii::Vector<double>
    ConstantRelaxation::compute_next(const dealii::Vector<double> &x,
                                     const dealii::Vector<double> &x_tilde)
    {
      dealii::Vector<double> next(x);
      next.sadd(1. - omega, omega, x_tilde);
      last_info            = AccelerationInfo();
      last_info.relaxation = omega;
      ++window_iteration;
      return next;
    }


    // ---------------------------------------------------------------------
    // AitkenRelaxation

    AitkenRelaxation::AitkenRelaxation(const double initial_relaxation)
      : omega_initial(initial_relaxation)
      , omega(initial_relaxation)
    {}


    std::string
    AitkenRelaxation::name() const
    {
      return "Aitken";
    }


    void
    AitkenRelaxation::start_window()
    {
      InterfaceAccelerator::start_window();
      have_previous = false;
    }


    dealii::Vector<double>
    AitkenRelaxation::compute_next(const dealii::Vector<double> &x,
                                   const dealii::Vector<double> &x_tilde)
    {
      dealii::Vector<double> residual(x_tilde);
      residual -= x;
      const double residual_norm = residual.l2_norm();

      last_info = AccelerationInfo();
      if (window_iteration == 0)
        // preCICE: start from the last factor, at most the initial one.
        omega = std::copysign(std::min(omega_initial, std::abs(omega)), omega);
      else if (residual_norm > 0.)
        {
          bool                   secant = false;
          dealii::Vector<double> difference(residual);
          difference -= previous_residual;
          const double previous_norm   = previous_residual.l2_norm();
          const double difference_norm = difference.l2_norm();
          if (have_previous && previous_norm > 0. &&
              difference_norm >
                roundoff_difference * std::max(residual_norm, previous_norm))
            {
              const double candidate = -omega *
                                       (previous_residual * difference) /
                                       (difference_norm * difference_norm);
              if (std::isfinite(candidate) && candidate != 0.)
                {
                  omega  = candidate;
                  secant = true;
                }
            }
          if (!secant)
            {
              omega              = omega_initial;
              last_info.fallback = true;
            }
        }

      dealii::Vector<double> next(x);
      if (residual_norm > 0.)
        next.add(omega, residual);
      last_info.relaxation = omega;
      previous_residual    = residual;
      have_previous        = true;
      ++window_iteration;
      return next;
    }


    void
    AitkenRelaxation::reset()
    {
      InterfaceAccelerator::reset();
      omega         = omega_initial;
      have_previous = false;
    }


    double
    AitkenRelaxation::relaxation() const
    {
      return omega;
    }


    // ---------------------------------------------------------------------
    // IQNILS

    IQNILS::IQNILS(const double       initial_relaxation,
                   const unsigned int reuse,
                   const unsigned int maximum_columns,
                   const Filter       filter,
                   const double       filter_tolerance)
      : omega_initial(initial_relaxation)
      , reuse(reuse)
      , maximum_columns(std::max(1U, maximum_columns))
      , filter(filter)
      , filter_tolerance(filter_tolerance)
    {}


    std::string
    IQNILS::name() const
    {
      return "IQN-ILS";
    }


    void
    IQNILS::start_window()
    {
      InterfaceAccelerator::start_window();
      initial_jacobian = nullptr;
      if (window_converged)
        ++window;
      window_converged = false;
      have_previous    = false;
      stagnated        = false;
      // The last window's columns serve the first iteration even if q = 0.
      drop_old_columns(std::max(reuse, 1U));
    }


    void
    IQNILS::add_differences(const dealii::Vector<double> &residual,
                            const dealii::Vector<double> &x_tilde)
    {
      if (have_previous)
        {
          Column column{residual, x_tilde, window};
          column.delta_residual -= previous_residual;
          column.delta_x_tilde -= previous_x_tilde;
          const double residual_norm = residual.l2_norm();
          const double difference    = column.delta_residual.l2_norm();
          // The last step hardly changed a nonzero residual: the model
          // returned (nearly) the point it had, and with the new column
          // filtered out it would do so again for ever (seen with QR1 on a
          // piecewise-linear contact operator); the next step relaxes.
          stagnated = residual_norm > 0. &&
                      difference <= stagnation_ratio * residual_norm;
          if (difference >
              roundoff_difference *
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
    IQNILS::drop_old_columns(const unsigned int max_age)
    {
      columns.erase(std::remove_if(columns.begin(),
                                   columns.end(),
                                   [&](const Column &c) {
                                     return window - c.window > max_age;
                                   }),
                    columns.end());
      // Without a filter, more columns than interface DoFs are dependent
      // and nothing removes them: keep at most as many as the residual has
      // entries, the newest (preCICE's 'overdetermined' rule). The filters
      // choose among all columns themselves (QR2 keeps the newest
      // independent ones, which caps them at the DoFs as well).
      const std::size_t rows = (filter == Filter::none && !columns.empty() ?
                                  columns.front().delta_residual.size() :
                                  maximum_columns);
      while (columns.size() > std::min<std::size_t>(maximum_columns, rows))
        columns.pop_back();
    }


    dealii::Vector<double>
    IQNILS::compute_next(const dealii::Vector<double> &x,
                         const dealii::Vector<double> &x_tilde)
    {
      dealii::Vector<double> residual(x_tilde);
      residual -= x;
      add_differences(residual, x_tilde);
      drop_old_columns(window_iteration == 0 ? std::max(reuse, 1U) : reuse);

      last_info             = AccelerationInfo();
      const bool first_ever = (window == 0 && window_iteration == 0);
      ++window_iteration;

      // Least-squares model min |V c + r| from the columns, newest first,
      // filtered while the QR factorisation is built.
      dealii::QR<dealii::Vector<double>> qr;
      std::vector<unsigned int>          kept;
      unsigned int                       removed = 0;
      if (!first_ever && !stagnated)
        {
          // the removed columns are deleted from V and W for good
          removed = internal::filter_columns(
            columns, filter, filter_tolerance, qr, kept);
          filtered_total += removed;
        }
      last_info.filtered_columns = removed;

      dealii::Vector<double> next(x_tilde);
      if (qr.size() == 0 && initial_jacobian)
        {
          // the step of the initial Jacobian alone: x~ - J0 r
          dealii::Vector<double> J0r(x.size());
          initial_jacobian(residual, J0r);
          next -= J0r;
          last_info.quasi_newton = true;
          stagnated              = false;
          return next;
        }
      if (qr.size() == 0)
        {
          // No model: relax (first iteration ever, or every column gone).
          next = x;
          next.add(omega_initial, residual);
          last_info.relaxation = omega_initial;
          last_info.fallback   = !first_ever;
          stagnated            = false;
          return next;
        }

      dealii::Vector<double> qt_r(qr.size());
      qr.multiply_with_QT(qt_r, residual);
      dealii::Vector<double> c(qr.size());
      qr.solve(c, qt_r);
      for (unsigned int j = 0; j < kept.size(); ++j)
        next.add(-c[j], columns[kept[j]].delta_x_tilde);
      if (initial_jacobian)
        {
          // - J0 (r - V c): J0 on what the columns do not explain
          dealii::Vector<double> unexplained(residual), J0u(x.size());
          for (unsigned int j = 0; j < kept.size(); ++j)
            unexplained.add(-c[j], columns[kept[j]].delta_residual);
          initial_jacobian(unexplained, J0u);
          next -= J0u;
        }
      last_info.quasi_newton = true;
      last_info.columns      = qr.size();
      return next;
    }


    void
    IQNILS::end_window(const dealii::Vector<double> &x,
                       const dealii::Vector<double> &x_tilde)
    {
      dealii::Vector<double> residual(x_tilde);
      residual -= x;
      add_differences(residual, x_tilde);
      drop_old_columns(std::max(reuse, 1U));
      window_converged = true;
    }


    void
    IQNILS::reset()
    {
      InterfaceAccelerator::reset();
      columns.clear();
      have_previous    = false;
      stagnated        = false;
      window           = 0;
      window_converged = false;
      filtered_total   = 0;
    }


    void
    IQNILS::set_initial_jacobian(
      const std::function<void(const dealii::Vector<double> &,
                               dealii::Vector<double> &)> &J0)
    {
      initial_jacobian = J0;
      // J0 of this window replaces the columns of past windows: they are
      // secants of the operators of other steps (another P2G, another
      // tangent), and the least-change update would bend J0 to fit them
      // (block on the string with mass: 6.54 iterations per step with 10
      // reused windows, 3.5 without)
      columns.erase(std::remove_if(columns.begin(),
                                   columns.end(),
                                   [this](const Column &c) {
                                     return c.window != window;
                                   }),
                    columns.end());
    }


    unsigned int
    IQNILS::n_columns() const
    {
      return columns.size();
    }


    unsigned int
    IQNILS::n_filtered_columns() const
    {
      return filtered_total;
    }


    // ---------------------------------------------------------------------
    // Parameters

    void
    AccelerationParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      using dealii::Patterns::Selection;
      prm.declare_entry(
        "acceleration",
        "IQN-ILS",
        Selection("constant|Aitken|IQN-ILS|IQN-IMVJ"),
        "Convergence acceleration of the interface iteration: constant "
        "under-relaxation, Aitken's dynamic relaxation, interface "
        "quasi-Newton with a least-squares inverse Jacobian (IQN-ILS), or "
        "with an explicit inverse Jacobian carried from window to window "
        "(IQN-IMVJ, multi-vector update; n x n doubles on every rank, at "
        "most 5000 interface DoFs).");
      prm.declare_entry("relaxation",
                        "0.5",
                        Double(),
                        "Constant relaxation factor omega [-], in (0, 1] "
                        "(acceleration = constant). Optimal for two springs: "
                        "k_N/(k_N + k_D).");
      prm.declare_entry("initial relaxation",
                        "0.1",
                        Double(),
                        "Relaxation factor [-], in (0, 1], of Aitken's first "
                        "window and of the first iteration of IQN-ILS and "
                        "IQN-IMVJ (and of their fall-back steps without "
                        "secant or column information). preCICE: 0.1 for "
                        "IQN-ILS, 0.5 for Aitken.");
      prm.declare_entry("IQN-ILS reuse",
                        "10",
                        Integer(),
                        "Number of past time windows [-], >= 0, whose "
                        "residual differences IQN-ILS keeps in its "
                        "least-squares model (preCICE 'time-windows-reused'); "
                        "not used by IQN-IMVJ, whose inverse Jacobian carries "
                        "the past windows.");
      prm.declare_entry("IQN-ILS maximum columns",
                        "100",
                        Integer(),
                        "Largest number of columns [-], >= 1, of the IQN-ILS "
                        "least-squares model (of IQN-IMVJ: per window); the "
                        "oldest are dropped (preCICE 'max-used-iterations').");
      prm.declare_entry(
        "QR filter",
        "QR2",
        Selection("none|QR1|QR2"),
        "Filter of (nearly) linearly dependent IQN-ILS and "
        "IQN-IMVJ columns: QR1 removes column i if |R_ii| < tol "
        "|R|_F, QR2 skips a column whose part orthogonal to "
        "the newer ones is below tol times its norm; none "
        "keeps all but those dependent to round-off.");
      prm.declare_entry("QR filter tolerance",
                        "1e-2",
                        Double(),
                        "Tolerance of the QR filter [-], > 0 (preCICE "
                        "suggests 1e-6 ... 1e-5 for QR1, 1e-3 ... 1e-2 for "
                        "QR2).");
    }


    void
    AccelerationParameters::parse_parameters(dealii::ParameterHandler &prm,
                                             const std::string &subsection)
    {
      const std::string m = prm.get("acceleration");
      method              = (m == "constant" ? Method::constant :
                             m == "Aitken"   ? Method::Aitken :
                             m == "IQN-IMVJ" ? Method::IQN_IMVJ :
                                               Method::IQN_ILS);
      relaxation          = internal::get_in_half_open_interval(
        prm, subsection, "relaxation", 0., 1.);
      initial_relaxation = internal::get_in_half_open_interval(
        prm, subsection, "initial relaxation", 0., 1.);
      reuse =
        internal::get_integer_at_least(prm, subsection, "IQN-ILS reuse", 0);
      maximum_columns = internal::get_integer_at_least(
        prm, subsection, "IQN-ILS maximum columns", 1);
      const std::string f = prm.get("QR filter");
      filter              = (f == "none" ? IQNILS::Filter::none :
                             f == "QR1"  ? IQNILS::Filter::QR1 :
                                           IQNILS::Filter::QR2);
      filter_tolerance = get_positive(prm, subsection, "QR filter tolerance");
    }


    std::unique_ptr<InterfaceAccelerator>
    create_accelerator(const AccelerationParameters &p)
    {
      switch (p.method)
        {
          case AccelerationParameters::Method::constant:
            return std::make_unique<ConstantRelaxation>(p.relaxation);
          case AccelerationParameters::Method::Aitken:
            return std::make_unique<AitkenRelaxation>(p.initial_relaxation);
          case AccelerationParameters::Method::IQN_IMVJ:
            return std::make_unique<IQNIMVJ>(p.initial_relaxation,
                                             p.maximum_columns,
                                             p.filter,
                                             p.filter_tolerance);
          case AccelerationParameters::Method::IQN_ILS:
          default:
            return std::make_unique<IQNILS>(p.initial_relaxation,
                                            p.reuse,
                                            p.maximum_columns,
                                            p.filter,
                                            p.filter_tolerance);
        }
    }
  } // namespace Coupling
} // namespace Talus
