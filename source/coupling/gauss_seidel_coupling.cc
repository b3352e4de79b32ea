#include <talus/base/input.h>
#include <talus/coupling/gauss_seidel_coupling.h>

#include <deal.II/base/mpi.h>

#include <deal.II/lac/sparse_direct.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <stdexcept>

namespace Talus
{
  namespace Coupling
  {
    namespace
    {
      /** A field's Newton failed inside a coupling iteration. */
      struct FieldFailed : EvaluationFailed
      {
        using EvaluationFailed::EvaluationFailed;
      };
    } // namespace


    template <int dim>
    GaussSeidelCoupling<dim>::GaussSeidelCoupling(
      MPM::MPMProblem<dim>        &mpm,
      Structure::StructureProblem &structure,
      StructureInterface<dim>     &interface,
      const CouplingParameters    &parameters,
      dealii::TimerOutput         &timer,
      const MPI_Comm               communicator)
      : mpm(mpm)
      , structure(structure)
      , interface(interface)
      , parameters(parameters)
      , timer(timer)
      , communicator(communicator)
      , acceleration(create_accelerator(parameters.acceleration))
      , criterion(parameters.criterion)
      , predictor(parameters.predictor)
    {}


    template <int dim>
    void
    GaussSeidelCoupling<dim>::initialize(const double t0)
    {
      committed = structure.displacement();
      force.reinit(committed.size());
      committed_force.reinit(committed.size());
      interface.set_step_displacement(committed, committed, t0, t0);
      mpm.boundaries().move_to(t0);
      mpm.initialize(t0);
      predictor.clear();
      predictor.add_converged(t0, committed);
      step_end = t0;
    }


    template <int dim>
    unsigned int
    GaussSeidelCoupling<dim>::solve_structure(const double                  t,
                                              const double                  dt,
                                              const dealii::Vector<double> &F,
                                              CoupledStepResult<dim> &result)
    {
      dealii::TimerOutput::Scope scope(timer, "coupling: structure");
      structure.set_interface_forces(F);
      // static: the equilibrium under the full loads (load factor 1)
      if (structure.is_dynamic())
        structure.prepare_step(t, dt);
      else
        structure.prepare_step(0., 1.);
      const auto status = structure.solve_step();
      result.structure_newton += status.iterations;
      if (!status.converged)
        throw FieldFailed("the structure did not converge: " + status.failure);
      return status.iterations;
    }


    template <int dim>
    CoupledStepResult<dim>
    GaussSeidelCoupling<dim>::solve_step(const double t, const double dt)
    {
      CoupledStepResult<dim> result;
      step_end = t + dt;
      mpm.solver().set_warm_start(false);
      dealii::Vector<double> springs, last_x;
      // the interface points loaded in the last iteration of this window,
      // and whether the last evaluation changed them
      std::vector<bool> active_set;
      bool              set_changed = false;
      structure.set_interface_springs(dealii::Vector<double>(),
                                      dealii::Vector<double>());
      const bool strong =
        parameters.scheme == CouplingParameters::Scheme::strong;
      static const bool debug = std::getenv("TALUS_DEBUG_COUPLING") != nullptr;
      // whether this window's MPM step was prepared (by the first
      // evaluation of H)
      bool mpm_prepared = false;
      // whether the window's initial Jacobian is still to be computed
      bool jacobian_pending = parameters.interface_stiffness_jacobian && strong;

      // The fixed-point operator x -> x̃ of the Dirichlet-Neumann iteration.
      const auto H = [&](const dealii::Vector<double> &x,
                         dealii::Vector<double>       &x_tilde,
                         dealii::Vector<double>       &f) {
        {
          dealii::TimerOutput::Scope scope(timer, "coupling: MPM");
          interface.set_step_displacement(committed, x, t, t + dt);
          // within the window only the interface moves: the P2G (and the
          // pattern, where the boundary cells stay) of the first iteration
          // is kept, with bitwise the same result (doc/coupling.md)
          if (mpm_prepared)
            mpm.update_boundary_displacement();
          else
            mpm.prepare_step(t + dt, dt);
          mpm_prepared = true;
          result.mpm   = mpm.solve_step();
          result.mpm_newton += result.mpm.iterations;
          // the next iteration of this window starts from this increment
          mpm.solver().set_warm_start(parameters.warm_start &&
                                      result.mpm.converged);
        }
        if (!result.mpm.converged)
          throw FieldFailed("the MPM did not converge: " + result.mpm.failure);
        {
          dealii::TimerOutput::Scope scope(timer, "coupling: transfer");
          const auto reactions = mpm.solver().boundary_reactions();
          force                = interface.structure_forces(reactions,
                                             committed.size(),
                                             communicator);
          if (parameters.restart_at_contact_change)
            {
              // the same on every rank: the loaded points are gathered
              auto loaded = interface.loaded_points();
              set_changed = !active_set.empty() && loaded != active_set;
              active_set  = std::move(loaded);
            }
          // Robin springs where this MPM solve transmits force: a contact
          // interface that opens in an iterate must not be held by them
          // (with springs fixed from the first solve of the window, an
          // iterate that pulls the structure away from the material sees
          // x~ = x up to k/(K + k) and stalls: the rebound of a dropped
          // block did not converge). At the fixed point x~ = x the springs
          // carry no force, whatever they are.
          if (robin_stiffness(dt) > 0.)
            {
              springs = interface.covered_area(reactions,
                                               committed.size(),
                                               communicator,
                                               normal_springs());
              // (with the interface force at its end value the
              // material's incremental interface stiffness is 1/(2 beta)
              // times the trapezoidal one, and the structure counts the
              // force (1 - alpha)/(2 beta) times: for alpha = 0 the
              // springs stay those of the trapezoidal rule; scaled by
              // the factor, the dropped block took 4.65 instead of 4.26
              // coupling iterations per step)
              springs *= robin_stiffness(dt);
            }
        }
        if (springs.size() > 0)
          structure.set_interface_springs(springs, x);
        last_x                 = x;
        const unsigned int its = solve_structure(t, dt, force, result);
        x_tilde                = structure.displacement();
        f                      = force;
        if (jacobian_pending)
          {
            // the window's initial Jacobian from the tangents of this first
            // evaluation (the accelerator started the window before it)
            jacobian_pending = false;
            if (compute_interface_jacobian(springs))
              acceleration->set_initial_jacobian(
                [this](const dealii::Vector<double> &v,
                       dealii::Vector<double>       &Jv) {
                  apply_initial_jacobian(v, Jv);
                });
          }
        if (debug &&
            dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
          {
            dealii::Vector<double> r(x_tilde);
            r -= x;
            // the residual at the interface points by component (root of
            // the sum of squares over the points)
            double r_component[3] = {0., 0., 0.};
            for (const auto &u : interface.point_displacements(r))
              for (unsigned int d = 0; d < dim; ++d)
                r_component[d] += u[d] * u[d];
            std::cerr << "coupling t = " << t + dt << "  |x| " << x.l2_norm()
                      << "  |x~| " << x_tilde.l2_norm() << "  |r| "
                      << r.l2_norm() << "  points: |r_x| "
                      << std::sqrt(r_component[0]) << "  |r_y| "
                      << std::sqrt(r_component[1]) << "  |r_z| "
                      << std::sqrt(r_component[2]) << "  |F| "
                      << force.l2_norm() << "  MPM Newton "
                      << result.mpm.iterations << "  structure Newton " << its
                      << "  springs " << springs.l1_norm() << '\n';
          }
      };

      try
        {
          dealii::Vector<double> x0;
          if (parameters.order == CouplingParameters::Order::structure_first)
            {
              // the structure first, with the last step's forces
              solve_structure(t, dt, committed_force, result);
              x0 = structure.displacement();
            }
          else
            x0 = predictor.predict(t + dt);
          dealii::TimerOutput::Scope scope(timer, "coupling: iteration");
          // with Robin springs: the structure's equilibrium defect
          const auto defect = [&]() {
            if (springs.size() == 0)
              return 0.;
            double d = 0.;
            for (unsigned int i = 0; i < springs.size(); ++i)
              d += dealii::Utilities::fixed_power<2>(
                springs[i] * (structure.displacement()[i] - last_x[i]));
            d = std::sqrt(d);
            // below the absolute displacement tolerance: no defect
            if (d <= springs.linfty_norm() * criterion.absolute_tolerance())
              return 0.;
            return d / std::max(
                         {force.l2_norm(), committed_force.l2_norm(), 1e-300});
          };
          const WindowResult window = iterate_window(
            H,
            x0,
            *acceleration,
            criterion,
            strong,
            robin_stiffness(dt) > 0. ? std::function<double()>(defect) :
                                       std::function<double()>(),
            parameters.restart_at_contact_change ?
              std::function<bool()>([&]() { return set_changed; }) :
              std::function<bool()>());
          result.iterations       = window.iterations;
          result.restarts         = window.restarts;
          result.contact_restarts = window.contact_restarts;
          if (!window.history.empty())
            result.status = window.history.back().status;
          for (const auto &record : window.history)
            if (record.acceleration.relaxation != 0.)
              result.relaxation = record.acceleration.relaxation;
          if (!window.accepted)
            result.failure = "the interface did not converge in " +
                             std::to_string(window.iterations) +
                             " coupling iterations (" +
                             result.status.to_string() + ")";
        }
      catch (const FieldFailed &e)
        {
          result.failure = e.what();
        }
      if (!result.failure.empty())
        {
          structure.set_interface_springs(dealii::Vector<double>(),
                                          dealii::Vector<double>());
          return result;
        }
      structure.set_interface_springs(dealii::Vector<double>(),
                                      dealii::Vector<double>());
      result.converged = true;
      for (unsigned int d = 0; d < dim; ++d)
        result.interface_force[d] = interface.total_particle_force()[d];
      const auto work =
        interface.interface_work(structure.displacement(), force);
      result.work_structure = work.first;
      result.work_points    = work.second;
      {
        const bool  end_value = parameters.interface_force_at_end;
        const auto &u         = structure.displacement();
        for (unsigned int i = 0; i < force.size(); ++i)
          result.interface_work +=
            (end_value ? force[i] : 0.5 * (force[i] + committed_force[i])) *
            (u[i] - committed[i]);
      }
      return result;
    }


    template <int dim>
    bool
    GaussSeidelCoupling<dim>::compute_interface_jacobian(
      const dealii::Vector<double> &springs)
    {
      dealii::TimerOutput::Scope scope(timer, "coupling: interface Jacobian");
      // the MPM linearises penalty and augmented Lagrangian conditions only
      for (const unsigned int b : interface.boundary_indices())
        {
          const auto &boundary = mpm.boundaries().boundary(b);
          if (boundary.nitsche || boundary.lagrange_multiplier)
            InputFile::reject("Coupling",
                              "initial Jacobian",
                              "interface stiffness",
                              "'none' when an interface boundary imposes "
                              "its condition by " +
                                std::string(boundary.nitsche ?
                                              "Nitsche's method" :
                                              "Lagrange multipliers") +
                                " (boundary '" + boundary.name +
                                "'; interface stiffness needs a penalty or "
                                "augmented Lagrangian method)");
        }
      const auto &constraints = structure.get_structure().get_constraints();
      const unsigned int                           n = committed.size();
      std::vector<dealii::types::global_dof_index> dofs;
      for (const auto j : interface.interface_structure_dofs())
        if (!constraints.is_constrained(j))
          dofs.push_back(j);
      AssertThrow(dofs.size() <= 5000,
                  dealii::ExcMessage(
                    "initial Jacobian = interface stiffness: the interface "
                    "has " +
                    std::to_string(dofs.size()) +
                    " free DoFs, at most 5000 are allowed (set initial "
                    "Jacobian = none)"));
      // the change of every interface point's prescribed increment for a
      // unit displacement of each interface DoF at the end of the step,
      // for the DoFs that move a point loaded in this evaluation (the
      // others neither move the material nor carry a spring)
      std::vector<std::vector<dealii::Tensor<1, dim>>> delta;
      {
        const std::vector<bool> loaded = interface.loaded_points();
        std::vector<dealii::types::global_dof_index> moving;
        dealii::Vector<double>                       e(n);
        for (const auto j : dofs)
          {
            e[j]       = 1.;
            auto u     = interface.point_displacements(e);
            e[j]       = 0.;
            bool moves = false;
            for (unsigned int p = 0; p < u.size() && !moves; ++p)
              moves = p < loaded.size() && loaded[p] && u[p].norm() > 0.;
            if (moves)
              {
                moving.push_back(j);
                delta.push_back(std::move(u));
              }
          }
        dofs = std::move(moving);
      }
      // the same on every rank (the loaded points are gathered)
      if (dofs.empty())
        return false;
      const auto reactions = mpm.solver().linearised_boundary_reactions(
        [&](const dealii::types::particle_index id, const unsigned int c) {
          const unsigned int p = interface.point_of(id);
          return p == dealii::numbers::invalid_unsigned_int ?
                   dealii::Tensor<1, dim>() :
                   delta[c][p];
        },
        dofs.size());
      // dF/dx e_j = -K_D e_j on the structure's DoFs
      const auto dF =
        interface.linearised_structure_forces(reactions, n, communicator);

      // U = C (k - K_D) on the columns where k - K_D acts
      std::vector<dealii::Vector<double>>          columns;
      std::vector<dealii::types::global_dof_index> S;
      bool                                         any_force = false;
      // (the structure takes the force interface_force_factor() times)
      for (unsigned int c = 0; c < dofs.size(); ++c)
        {
          dealii::Vector<double> v(dF[c]);
          v *= structure.interface_force_factor();
          any_force = any_force || v.linfty_norm() > 0.;
          if (springs.size() == n)
            v[dofs[c]] += springs[dofs[c]];
          constraints.set_zero(v);
          if (v.linfty_norm() > 0.)
            {
              columns.push_back(std::move(v));
              S.push_back(dofs[c]);
            }
        }
      if (!any_force || S.empty())
        return false;
      dealii::SparseDirectUMFPACK compliance;
      compliance.initialize(structure.get_static_solver().tangent());
      const unsigned int m = S.size();
      jacobian_U.reinit(n, m);
      for (unsigned int c = 0; c < m; ++c)
        {
          compliance.solve(columns[c]);
          constraints.set_zero(columns[c]);
          for (unsigned int i = 0; i < n; ++i)
            jacobian_U(i, c) = columns[c][i];
        }
      dealii::FullMatrix<double> I_minus_US(m, m);
      for (unsigned int a = 0; a < m; ++a)
        for (unsigned int b = 0; b < m; ++b)
          I_minus_US(a, b) = (a == b ? 1. : 0.) - jacobian_U(S[a], b);
      jacobian_M.reinit(m, m);
      jacobian_M.invert(I_minus_US);
      jacobian_dofs = std::move(S);
      return true;
    }


    template <int dim>
    void
    GaussSeidelCoupling<dim>::apply_initial_jacobian(
      const dealii::Vector<double> &v,
      dealii::Vector<double>       &result) const
    {
      // J0 v = A (A - I)^-1 v = -U M v_S
      const unsigned int     m = jacobian_dofs.size();
      dealii::Vector<double> v_S(m), z(m);
      for (unsigned int a = 0; a < m; ++a)
        v_S[a] = v[jacobian_dofs[a]];
      jacobian_M.vmult(z, v_S);
      result.reinit(v.size());
      jacobian_U.vmult(result, z);
      result *= -1.;
    }


    template <int dim>
    double
    GaussSeidelCoupling<dim>::robin_stiffness(const double dt) const
    {
      if (!parameters.robin_inertia)
        return parameters.robin_stiffness;
      const double h = mpm.grid().minimal_cell_diameter / std::sqrt(1. * dim);
      const double d = parameters.robin_depth * h;
      // no inertia in a quasi-static MPM (rho d / (beta dt^2) would be
      // 1.6e11 Pa/m at dt = 1e-3 s for no physical reason)
      const double inertia =
        mpm.solver().is_quasi_static() ?
          0. :
          mpm.density() * d * mpm.time_integrator().mass_factor(dt);
      const double layer =
        inertia +
        (parameters.robin_elastic ? mpm.model().p_wave_modulus() / d : 0.);
      // A penalty spring of stiffness beta per area between the interface
      // and the material acts in series with the layer: with the soft
      // penalty of material-point contact (beta = 0.1 M / h) the layer alone
      // overestimated the material side's stiffness 4-8 times and a
      // granular column on a string took 12.4 instead of 6.6 coupling
      // iterations per step (doc/coupling.md).
      double beta = std::numeric_limits<double>::max();
      for (const unsigned int b : interface.boundary_indices())
        {
          const auto &boundary = mpm.boundaries().boundary(b);
          if (!boundary.augmented && !boundary.nitsche &&
              !boundary.lagrange_multiplier && boundary.beta > 0.)
            beta = std::min(beta, boundary.beta);
        }
      if (beta == std::numeric_limits<double>::max() || !(layer > 0.))
        return layer;
      return 1. / (1. / layer + 1. / beta);
    }


    template <int dim>
    bool
    GaussSeidelCoupling<dim>::normal_springs() const
    {
      using Directions = CouplingParameters::RobinDirections;
      if (parameters.robin_directions != Directions::automatic)
        return parameters.robin_directions == Directions::normal;
      for (const unsigned int b : interface.boundary_indices())
        {
          const auto condition = mpm.boundaries().boundary(b).condition;
          if (condition != Boundaries::Condition::slip &&
              condition != Boundaries::Condition::contact)
            return false;
        }
      return true;
    }


    template <int dim>
    void
    GaussSeidelCoupling<dim>::commit_step()
    {
      mpm.commit_step();
      structure.commit_step();
      committed       = structure.displacement();
      committed_force = force;
      predictor.add_converged(step_end, committed);
      // the boundary particles at the committed interface displacement
      interface.set_step_displacement(committed, committed, step_end, step_end);
    }


    template <int dim>
    void
    GaussSeidelCoupling<dim>::reject_step()
    {
      acceleration->reset();
      criterion.reset();
    }


    template <int dim>
    void
    GaussSeidelCoupling<dim>::save_state()
    {
      mpm.save_state();
      structure.save_state();
      saved_committed       = committed;
      saved_committed_force = committed_force;
      saved_predictor       = predictor;
    }


    template <int dim>
    void
    GaussSeidelCoupling<dim>::restore_state(const double t)
    {
      mpm.restore_state();
      structure.restore_state();
      committed       = saved_committed;
      committed_force = saved_committed_force;
      force           = committed_force;
      predictor       = saved_predictor;
      step_end        = t;
      // the boundary particles at the committed interface displacement
      interface.set_step_displacement(committed, committed, t, t);
      reject_step();
    }


    template class GaussSeidelCoupling<2>;
    template class GaussSeidelCoupling<3>;
  } // namespace Coupling
} // namespace Talus
