#ifndef talus_coupling_qr_filter_h
#define talus_coupling_qr_filter_h

// The filtered QR factorisation of the residual differences V shared by
// IQN-ILS and IQN-IMVJ (accelerators.h, iqn_imvj.h), and their round-off
// constants.

#include <talus/coupling/accelerators.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/qr.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <vector>

namespace Talus
{
  namespace Coupling
  {
    namespace internal
    {
      /** A residual difference below this fraction of the residuals is
       * round-off: no secant (Aitken), no column (IQN-ILS, IQN-IMVJ). */
      constexpr double roundoff_difference = 1e-14;

      /** A column whose part orthogonal to the kept ones is below this
       * fraction of its norm is dependent to round-off. */
      constexpr double roundoff_dependence = 1e-12;

      /** IQN-ILS, IQN-IMVJ: a step that changed a nonzero residual by less
       * than this fraction brought no information (stagnation guard). */
      constexpr double stagnation_ratio = 1e-3;

      /**
       * Factorise the columns @p v (newest first) into @p qr, appending a
       * column only if its part orthogonal to those kept is at least
       * max(ε, 1e-12) (QR2) or 1e-12 (otherwise) times its norm, then (QR1)
       * removing column i while |R_ii| < ε ‖R‖_F. @p kept receives the
       * indices into @p v of Q's columns, in order; returns the number of
       * columns left out.
       */
      inline unsigned int
      build_filtered_qr(const std::vector<const dealii::Vector<double> *> &v,
                        const IQNILS::Filter                filter,
                        const double                        filter_tolerance,
                        dealii::QR<dealii::Vector<double>> &qr,
                        std::vector<unsigned int>          &kept)
      {
        unsigned int removed = 0;
        kept.clear();
        for (unsigned int i = 0; i < v.size(); ++i)
          {
            const double v_norm          = v[i]->l2_norm();
            double       orthogonal_norm = v_norm;
            if (qr.size() > 0 && v_norm > 0.)
              {
                dealii::Vector<double> projection(qr.size());
                qr.multiply_with_QT(projection, *v[i]);
                dealii::Vector<double> orthogonal(v[i]->size());
                qr.multiply_with_Q(orthogonal, projection);
                orthogonal.sadd(-1., 1., *v[i]);
                orthogonal_norm = orthogonal.l2_norm();
              }
            const double limit =
              (filter == IQNILS::Filter::QR2 ?
                 std::max(filter_tolerance, roundoff_dependence) :
                 roundoff_dependence);
            if (v_norm > 0. && orthogonal_norm >= limit * v_norm)
              {
                qr.append_column(*v[i]);
                kept.push_back(i);
              }
            else
              ++removed;
          }

        if (filter == IQNILS::Filter::QR1)
          for (bool removing = true; removing && qr.size() > 1;)
            {
              removing                                    = false;
              const dealii::LAPACKFullMatrix<double> &R   = qr.get_R();
              double                                  sum = 0.;
              for (unsigned int i = 0; i < qr.size(); ++i)
                for (unsigned int j = i; j < qr.size(); ++j)
                  sum += R(i, j) * R(i, j);
              const double frobenius = std::sqrt(sum);
              for (unsigned int i = 0; i < qr.size(); ++i)
                if (std::abs(R(i, i)) < filter_tolerance * frobenius)
                  {
                    qr.remove_column(i);
                    kept.erase(kept.begin() + i);
                    ++removed;
                    removing = true;
                    break;
                  }
            }
        return removed;
      }
      /**
       * The filtered QR factorisation of the columns' residual differences
       * (build_filtered_qr()), with the removed columns deleted from
       * @p columns (V and W) for good; @p kept then lists the remaining
       * columns 0 .. n - 1. Returns the number of columns removed.
       */
      template <typename Column>
      unsigned int
      filter_columns(std::deque<Column>                 &columns,
                     const IQNILS::Filter                filter,
                     const double                        filter_tolerance,
                     dealii::QR<dealii::Vector<double>> &qr,
                     std::vector<unsigned int>          &kept)
      {
        std::vector<const dealii::Vector<double> *> v;
        for (const Column &column : columns)
          v.push_back(&column.delta_residual);
        const unsigned int removed =
          build_filtered_qr(v, filter, filter_tolerance, qr, kept);
        if (removed > 0)
          {
            std::deque<Column> remaining;
            for (const unsigned int i : kept)
              remaining.push_back(std::move(columns[i]));
            columns.swap(remaining);
            kept.clear();
            for (unsigned int i = 0; i < columns.size(); ++i)
              kept.push_back(i);
          }
        return removed;
      }
    } // namespace internal
  }   // namespace Coupling
} // namespace Talus

#endif
