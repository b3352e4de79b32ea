#include <talus/base/input.h>
#include <talus/structure/static_solver.h>

#include <deal.II/lac/sparse_direct.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

namespace Talus
{
  namespace Structure
  {
    namespace
    {
      double
      round_off_floor(const dealii::SparseMatrix<double>      &K,
                      const dealii::AffineConstraints<double> &constraints,
                      const dealii::Vector<double>            &u)
      {
        // |r| cannot fall below the change of r caused by representing u
        // itself: each u_j is known to eps |u_j|, so r_i to about
        // eps sum_j |K_ij| |u_j| (the componentwise bound of Oettli and
        // Prager). doc/theory.md, "Round-off floor of the Newton test".
        double s = 0.;
        for (unsigned int i = 0; i < K.m(); ++i)
          if (!constraints.is_constrained(i))
            {
              double row = 0.;
              for (auto it = K.begin(i); it != K.end(i); ++it)
                row += std::abs(it->value()) * std::abs(u[it->column()]);
              s += row * row;
            }
        return StaticSolver::round_off_factor *
               std::numeric_limits<double>::epsilon() * std::sqrt(s);
      }
    } // namespace


    StaticSolver::StaticSolver(Structure &structure)
      : structure(structure)
    {}


    void
    StaticSolver::declare_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Bool;
      using dealii::Patterns::Double;
      using dealii::Patterns::Integer;
      prm.enter_subsection("Solver");
      prm.declare_entry("load steps",
                        "10",
                        Integer(1),
                        "Number of equal load (or prescribed displacement) "
                        "increments from 0 to the full load [-].");
      prm.declare_entry("maximum Newton iterations",
                        "30",
                        Integer(1),
                        "Newton iterations allowed per load step [-].");
      prm.declare_entry("maximum step cuts",
                        "0",
                        Integer(0, 30),
                        "A load step whose Newton iteration fails is "
                        "restarted from the last converged state with half "
                        "the increment, up to this many times in a row "
                        "(0: fail at once) [-].");
      prm.declare_entry("predictor",
                        "constant",
                        dealii::Patterns::Selection("constant|secant"),
                        "Start of each load step: 'constant' (the last "
                        "converged displacement) or 'secant' (extrapolated "
                        "linearly in the load factor from the last two "
                        "converged states; a step that fails restarts from "
                        "the last converged state).");
      prm.declare_entry("tolerance",
                        "1e-10",
                        Double(0),
                        "Newton converges when |r| <= tolerance * max(|f_int|, "
                        "|f_ext|) (Euclidean norms over the free DoFs), or "
                        "when |r| reaches the round-off floor 10 eps "
                        "| |K| |u| | (doc/theory.md) [-].");
      prm.declare_entry("control",
                        "load",
                        dealii::Patterns::Selection("load|arc length"),
                        "Path following: 'load' (the load factor steps of "
                        "'load steps', displacement control through "
                        "prescribed displacements) or 'arc length' "
                        "(Crisfield's cylindrical arc-length method: the "
                        "load factor is an unknown, so the path passes "
                        "limit points; 'load steps' arc-length steps of "
                        "size 'arc length').");
      prm.declare_entry("arc length",
                        "0.01",
                        Double(),
                        "Arc-length step ds: norm of the displacement "
                        "increment of one step [m], > 0.");
      prm.declare_entry("maximum increment",
                        "0",
                        Double(0),
                        "Largest change of a displacement component in one "
                        "Newton iteration [m]; longer steps are scaled down. "
                        "0: no limit.");
      prm.declare_entry("line search",
                        "true",
                        Bool(),
                        "Backtracking line search on |r| (halving the Newton "
                        "step up to 10 times).");
      prm.leave_subsection();
    }


    void
    StaticSolver::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Solver");
      load_steps     = prm.get_integer("load steps");
      max_iterations = prm.get_integer("maximum Newton iterations");
      max_step_cuts  = prm.get_integer("maximum step cuts");
      predictor      = prm.get("predictor");
      tolerance      = get_positive(prm, "Structure/Solver", "tolerance");
      line_search    = prm.get_bool("line search");
      max_increment  = prm.get_double("maximum increment");
      control        = prm.get("control");
      arc_length     = get_positive(prm, "Structure/Solver", "arc length");
      prm.leave_subsection();
    }


    void
    StaticSolver::setup()
    {
      matrix.reinit(structure.get_sparsity_pattern());
      displacement.reinit(structure.n_dofs());
      previous_valid = false;
    }


    StaticSolver::History
    StaticSolver::get_history() const
    {
      History h;
      h.force_scale           = force_scale;
      h.previous_displacement = previous_displacement;
      h.previous_load_factor  = previous_load_factor;
      h.previous_valid        = previous_valid;
      return h;
    }


    void
    StaticSolver::set_history(const History &history)
    {
      force_scale           = history.force_scale;
      previous_displacement = history.previous_displacement;
      previous_load_factor  = history.previous_load_factor;
      previous_valid        = history.previous_valid;
    }


    NewtonStatus
    StaticSolver::solve_with_cuts(const double from, const double to)
    {
      dealii::Vector<double> converged = displacement;
      double                 reached = 0., step = 1.; // fractions of to-from
      unsigned int           cuts = 0, iterations = 0;
      NewtonStatus           status;
      bool                   retry = false;
      while (reached < 1.)
        {
          const double target      = std::min(1., reached + step);
          const double lambda_from = from + reached * (to - from);
          const double lambda = target == 1. ? to : from + target * (to - from);
          if (predictor == "secant" && !retry && previous_valid &&
              previous_load_factor != lambda_from)
            {
              // u = u_from + (lambda - lambda_from)/(lambda_from -
              // lambda_prev) (u_from - u_prev).
              const double factor =
                (lambda - lambda_from) / (lambda_from - previous_load_factor);
              dealii::Vector<double> d = converged;
              d -= previous_displacement;
              displacement = converged;
              displacement.add(factor, d);
            }
          status = solve(lambda);
          iterations += status.iterations;
          if (status.converged)
            {
              previous_displacement = converged;
              previous_load_factor  = lambda_from;
              previous_valid        = true;
              reached               = target;
              converged             = displacement;
              cuts                  = 0;
              retry                 = false;
              step                  = std::min(1., 2. * step);
            }
          else
            {
              if (++cuts > max_step_cuts)
                break;
              step *= 0.5;
              displacement = converged;
              retry        = true;
            }
        }
      status.iterations = iterations;
      return status;
    }


    NewtonStatus
    StaticSolver::solve(const double      load_factor,
                        const ExtraTerms &extra,
                        const bool        commit)
    {
      NewtonStatus           status;
      dealii::Vector<double> r, du, trial;
      structure.apply_prescribed(displacement, load_factor);
      const auto assemble = [&](const dealii::Vector<double> &u,
                                dealii::Vector<double>       &res,
                                dealii::SparseMatrix<double> *K) {
        double n = structure.assemble(u, load_factor, res, K);
        if (extra)
          {
            extra(u, res, K);
            n = res.l2_norm();
          }
        return n;
      };
      // Scale of the forces: the largest nodal force norm (reactions and
      // loads) of the converged states so far, or the initial residual of
      // this step if larger. Iterates never change it (a diverging iterate
      // must not loosen the tolerance).
      const auto nodal_force_norm = [&]() {
        double s = 0.;
        for (unsigned int i = 0; i < structure.n_nodes(); ++i)
          s += structure.reaction(i).norm_square();
        return std::sqrt(s);
      };
      double       norm = assemble(displacement, r, &matrix);
      double       mu   = 0.;
      const double reference =
        std::max({force_scale, nodal_force_norm(), 1e-300});
      for (unsigned int it = 0; it <= max_iterations; ++it)
        {
          status.iterations = it;
          status.residual   = norm;
          if (std::getenv("TALUS_DEBUG"))
            {
              std::cerr << "    it " << it << " |r| " << norm << " ref "
                        << reference << " round-off floor "
                        << round_off_floor(matrix,
                                           structure.get_constraints(),
                                           displacement)
                        << " mu " << mu << " slack:";
              for (const auto &m : structure.line_meshes)
                {
                  unsigned int n = 0;
                  for (const double f : m->force)
                    n += (f == 0.);
                  std::cerr << ' ' << m->name << '=' << n;
                }
              unsigned int nw = 0, nsl = 0, ns = 0;
              for (const auto &m : structure.membrane_meshes)
                for (const auto &o : m->cell_output)
                  {
                    nw += o.n_wrinkled;
                    nsl += o.n_slack;
                    ns += (o.min_principal < 0.);
                  }
              std::cerr << " net wrinkled/slack points, compressed cells " << nw
                        << '/' << nsl << '/' << ns << std::endl;
            }
          if (!std::isfinite(norm))
            {
              status.failure = "the residual is not finite";
              return status;
            }
          const double floor =
            round_off_floor(matrix, structure.get_constraints(), displacement);
          if (norm <= std::max(tolerance * reference, floor))
            {
              status.converged = true;
              if (commit)
                structure.commit_state();
              force_scale = std::max(force_scale, nodal_force_norm());
              return status;
            }
          if (it == max_iterations)
            break;
          if (std::getenv("TALUS_FD_CHECK") &&
              (it == 0 || std::string(std::getenv("TALUS_FD_CHECK")) == "all"))
            {
              // Debug: compare the tangent with central differences.
              dealii::Vector<double>       rp, rm, col(r.size()), e(r.size());
              double                       worst   = 0.;
              unsigned int                 worst_j = 0;
              dealii::SparseMatrix<double> K0;
              K0.reinit(structure.get_sparsity_pattern());
              K0.copy_from(matrix);
              for (unsigned int j = 0; j < r.size(); ++j)
                {
                  if (structure.get_constraints().is_constrained(j))
                    continue;
                  const double           h  = 1e-7;
                  dealii::Vector<double> up = displacement, um = displacement;
                  up[j] += h;
                  um[j] -= h;
                  structure.get_constraints().distribute(up);
                  structure.get_constraints().distribute(um);
                  assemble(up, rp, nullptr);
                  assemble(um, rm, nullptr);
                  e    = 0.;
                  e[j] = 1.;
                  K0.vmult(col, e);
                  double diff = 0., ref = 0.;
                  for (unsigned int i = 0; i < r.size(); ++i)
                    {
                      diff =
                        std::max(diff,
                                 std::abs((rp[i] - rm[i]) / (2. * h) - col[i]));
                      ref = std::max(ref, std::abs(col[i]));
                    }
                  if (diff / std::max(ref, 1e-300) > worst)
                    {
                      worst   = diff / std::max(ref, 1e-300);
                      worst_j = j;
                    }
                }
              std::cerr << "    FD check: worst column " << worst_j
                        << " rel. error " << worst << std::endl;
              assemble(displacement, r, &matrix);
            }

          // Newton direction from (K + mu I) du = -r. mu = 0 unless the
          // line search finds no decrease of |r|; then mu is raised
          // (Levenberg-Marquardt) until it does, and lowered again after
          // each successful step. mu changes only the iteration path, not
          // the solution (it never enters r). Needed for cable nets that
          // start stress-free (slack) and snap taut.
          const dealii::Vector<double> r0 = r;
          // |r| of the trial state; infinite where the trial state has no
          // stress (an inverted neo-Hookean solid throws): the line search
          // then shortens the step.
          const auto trial_norm = [&]() {
            try
              {
                return assemble(trial, r, nullptr);
              }
            catch (const std::exception &)
              {
                return std::numeric_limits<double>::infinity();
              }
          };
          double max_diagonal = 0.;
          for (unsigned int i = 0; i < matrix.m(); ++i)
            max_diagonal = std::max(max_diagonal, matrix.diag_element(i));
          double applied_mu = 0.;
          bool   decreased  = false;
          double new_norm   = norm;
          for (unsigned int attempt = 0; attempt < 12 && !decreased; ++attempt)
            {
              for (unsigned int i = 0; i < matrix.m(); ++i)
                if (!structure.get_constraints().is_constrained(i))
                  matrix.diag_element(i) += mu - applied_mu;
              applied_mu = mu;
              dealii::SparseDirectUMFPACK direct;
              try
                {
                  direct.initialize(matrix);
                }
              catch (const std::exception &e)
                {
                  status.failure =
                    "the tangent matrix cannot be factorised (singular: a "
                    "mechanism or a node without stiffness and mass)";
                  if (std::getenv("TALUS_DEBUG"))
                    std::cerr << e.what() << std::endl;
                  return status;
                }
              du = r0;
              direct.solve(du);
              du *= -1.;
              structure.get_constraints().distribute(du);
              if (max_increment > 0. && du.linfty_norm() > max_increment)
                du *= max_increment / du.linfty_norm();

              double alpha = 1.;
              trial        = displacement;
              trial.add(alpha, du);
              new_norm  = trial_norm();
              decreased = new_norm < (1. - 1e-4 * alpha) * norm;
              if (line_search)
                for (unsigned int k = 0; k < 6 && !decreased; ++k)
                  {
                    alpha *= 0.5;
                    trial = displacement;
                    trial.add(alpha, du);
                    new_norm  = trial_norm();
                    decreased = new_norm < (1. - 1e-4 * alpha) * norm;
                  }
              if (!line_search)
                decreased = true;
              if (!decreased)
                mu = std::min(mu == 0. ? 1e-8 * max_diagonal : 10. * mu,
                              1e4 * max_diagonal);
            }
          if (decreased)
            mu = (mu < 1e-7 * max_diagonal ? 0. : 0.1 * mu);
          else
            {
              // Neither the line search nor the largest shift reduces |r|:
              // stop rather than wander.
              status.failure = "no step reduces the residual (line search "
                               "and Levenberg-Marquardt exhausted)";
              displacement   = trial;
              return status;
            }
          displacement = trial;
          norm         = assemble(displacement, r, &matrix);
        }
      std::ostringstream msg;
      msg << "Newton did not converge in " << max_iterations
          << " iterations (|r| = " << norm << " N)";
      status.failure = msg.str();
      return status;
    }


    NewtonStatus
    StaticSolver::solve_arc_length(double                 &load_factor,
                                   const double            ds,
                                   dealii::Vector<double> &direction)
    {
      NewtonStatus           status;
      const auto            &constraints = structure.get_constraints();
      const unsigned int     n           = structure.n_dofs();
      dealii::Vector<double> r(n), r0(n), f_ref(n), du_R(n), du_F(n), Du(n);
      const dealii::Vector<double> u0      = displacement;
      const double                 lambda0 = load_factor;
      const auto free_dot = [&](const dealii::Vector<double> &a,
                                const dealii::Vector<double> &b) {
        double s = 0.;
        for (unsigned int i = 0; i < n; ++i)
          if (!constraints.is_constrained(i))
            s += a[i] * b[i];
        return s;
      };
      // Reference load vector f_ref = r(u, 0) - r(u, 1) (condensed) and the
      // residual and tangent at (u, lambda).
      const auto assemble = [&](const double lambda) {
        structure.assemble(displacement, 0., r0, nullptr);
        structure.assemble(displacement, 1., f_ref, nullptr);
        f_ref *= -1.;
        f_ref += r0;
        return structure.assemble(displacement, lambda, r, &matrix);
      };
      const auto solve = [&](const dealii::Vector<double> &rhs,
                             dealii::Vector<double>       &x) {
        dealii::SparseDirectUMFPACK direct;
        direct.initialize(matrix);
        x = rhs;
        direct.solve(x);
        constraints.distribute(x);
      };
      const auto nodal_force_norm = [&]() {
        double s = 0.;
        for (unsigned int i = 0; i < structure.n_nodes(); ++i)
          s += structure.reaction(i).norm_square();
        return std::sqrt(s);
      };

      try
        {
          // Predictor along the tangent, in the previous direction.
          assemble(load_factor);
          solve(f_ref, du_F);
          double dlambda =
            ds / std::sqrt(std::max(free_dot(du_F, du_F), 1e-300));
          if (direction.size() == n && free_dot(direction, du_F) < 0.)
            dlambda = -dlambda;
          Du = du_F;
          Du *= dlambda;
          load_factor += dlambda;
          displacement = u0;
          displacement += Du;

          for (unsigned int it = 0; it <= max_iterations; ++it)
            {
              const double norm = assemble(load_factor);
              const double reference =
                std::max({force_scale, nodal_force_norm(), 1e-300});
              status.iterations = it;
              status.residual   = norm;
              if (norm <=
                  std::max(tolerance * reference,
                           round_off_floor(matrix, constraints, displacement)))
                {
                  status.converged = true;
                  structure.commit_state();
                  force_scale = std::max(force_scale, nodal_force_norm());
                  direction   = Du;
                  return status;
                }
              if (it == max_iterations)
                break;
              dealii::Vector<double> minus_r = r;
              minus_r *= -1.;
              solve(minus_r, du_R);
              solve(f_ref, du_F);
              // |Du + du_R + dl du_F|^2 = ds^2.
              dealii::Vector<double> w = Du;
              w += du_R;
              const double a    = free_dot(du_F, du_F);
              const double b    = 2. * free_dot(du_F, w);
              const double c    = free_dot(w, w) - ds * ds;
              const double disc = b * b - 4. * a * c;
              if (disc < 0.)
                {
                  status.failure = "no intersection with the arc-length "
                                   "sphere (reduce 'arc length')";
                  break;
                }
              const double roots[2] = {(-b + std::sqrt(disc)) / (2. * a),
                                       (-b - std::sqrt(disc)) / (2. * a)};
              // The root that keeps going forward (largest Du_new . Du).
              double best = roots[0], best_cos = -1e300;
              for (const double dl : roots)
                {
                  dealii::Vector<double> Dn = w;
                  Dn.add(dl, du_F);
                  const double cos = free_dot(Dn, Du);
                  if (cos > best_cos)
                    {
                      best_cos = cos;
                      best     = dl;
                    }
                }
              Du = w;
              Du.add(best, du_F);
              load_factor += best;
              displacement = u0;
              displacement += Du;
            }
        }
      catch (const std::exception &)
        {
          status.failure = "the tangent matrix cannot be factorised";
        }
      if (status.failure.empty())
        status.failure = "the arc-length iteration did not converge in " +
                         std::to_string(max_iterations) + " iterations";
      displacement = u0;
      load_factor  = lambda0;
      return status;
    }
  } // namespace Structure
} // namespace Talus
