#include <talus/base/input.h>
#include <talus/coupling/coupling_parameters.h>

namespace Talus
{
  namespace Coupling
  {
    void
    CouplingParameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Coupling");
      {
        prm.declare_entry(
          "scheme",
          "strong",
          dealii::Patterns::Selection("strong|weak"),
          "strong: iterate each step until the interface converges "
          "(implicit Gauss-Seidel); weak: one pass of both solvers per step "
          "(explicit, staggered; unstable when the soil's interface "
          "stiffness including inertia exceeds the barrier's).");
        prm.declare_entry(
          "order",
          "MPM first",
          dealii::Patterns::Selection("MPM first|structure first"),
          "MPM first: the MPM gets the structure's interface displacement "
          "(Dirichlet), the structure the MPM's reactions (Neumann); the "
          "displacement is accelerated. structure first: the structure is "
          "solved first with the last reactions.");
        prm.declare_entry(
          "Robin stiffness",
          "automatic",
          dealii::Patterns::Anything(),
          "Interface springs of the structure during the iteration "
          "(Robin-Neumann, they vanish at convergence): 0 (plain "
          "Dirichlet-Neumann), a stiffness per interface area [Pa/m] >= 0, "
          "'inertia' (rho d / (beta dt^2): the inertia of a layer of "
          "material of depth d = 'Robin depth' cells behind the interface) "
          "or 'automatic' (that inertia plus the layer's stiffness M / d, M "
          "the p-wave modulus; no inertia term with a quasi-static MPM), "
          "both in series with the interface boundaries' penalty beta when "
          "they impose the condition by a penalty alone (k = 1/(1/k_layer "
          "+ 1/beta): a soft contact penalty is the softest part of the "
          "material side). Without it a heavy material on a light barrier "
          "makes the iteration diverge or need many iterations.");
        prm.declare_entry("Robin depth",
                          "4",
                          dealii::Patterns::Double(0.),
                          "Depth of the material layer of 'Robin stiffness "
                          "= inertia' [background cells], > 0.");
        prm.declare_entry(
          "Robin directions",
          "all",
          dealii::Patterns::Selection("all|normal|automatic"),
          "Components of the interface DoFs that carry Robin springs: all, "
          "normal (a point's spring k n n^T, lumped to its diagonal k "
          "n_d^2, n the direction of the point's reaction: no spring along "
          "an interface that transmits no tangential force) or automatic "
          "(normal when every interface boundary has condition slip or "
          "contact, all otherwise).");
        prm.declare_entry(
          "initial Jacobian",
          "none",
          dealii::Patterns::Selection("none|interface stiffness"),
          "Initial inverse Jacobian J0 of IQN-ILS (x_{k+1} = x~ - W c - "
          "J0 (r - V c)): none (the plain least-squares model; a window "
          "without columns relaxes with 'initial relaxation') or interface "
          "stiffness: J0 from the MPM's interface stiffness K_D (the "
          "derivative of its interface reactions with respect to the "
          "interface displacement, one back-substitution with the MPM's "
          "factorised tangent per interface DoF) and the structure's "
          "tangent, computed at the first iteration of every window; then "
          "the first step of a window is the Newton step of the linearised "
          "interface equilibrium, (K_S + K_D) dx = (K_S + k) r, and the "
          "columns of past windows are dropped (J0 carries what they "
          "would; doc/coupling.md). Only with acceleration = IQN-ILS, "
          "interface boundaries imposed by a penalty or an augmented "
          "Lagrangian, and at most 5000 interface DoFs.");
        prm.declare_entry(
          "restart at contact change",
          "false",
          dealii::Patterns::Bool(),
          "Restart the accelerator (forget its quasi-Newton columns, those "
          "of past windows and IQN-IMVJ's Jacobian; the next step relaxes "
          "with 'initial relaxation') whenever the set of interface points "
          "that carry a force changes between two iterations of a window "
          "(at most 6 times per window): a contact interface whose active "
          "set switches makes the iteration a different affine map on each "
          "set, and a model mixing them stalls (doc/coupling.md, "
          "'Iterations at contact'). Meant for a Robin iteration ('Robin "
          "stiffness' > 0): without springs the relaxation step after a "
          "restart can keep the set switching.");
        prm.declare_entry(
          "warm start",
          "false",
          dealii::Patterns::Bool(),
          "Start the MPM's Newton iteration of each coupling iteration after "
          "the first from the increment of the previous one (the step is "
          "the same, the interface moved a little) instead of from zero. "
          "Each MPM solve then depends on the last iterate to the Newton "
          "tolerance, which the interface iteration sees as noise: on the "
          "coupled tests it saved 14 % of the Newton iterations but cost "
          "more coupling iterations and no time (doc/coupling.md).");
        prm.declare_entry(
          "interface force in time",
          "trapezoidal",
          dealii::Patterns::Selection("trapezoidal|end of step"),
          "How the contact force of the interface boundaries acts within a "
          "dynamic step. 'trapezoidal': through both Newmark schemes' "
          "accelerations, as every other force; a contact that closes "
          "within a step then does work that no account books (a boulder "
          "striking the net of the 2D flagship analogue: about 6 kJ/m). "
          "'end of step': with its end value over the whole step, on the "
          "material as 'contact force in time = end of step' in subsection "
          "Solver (required) acts at boundaries at rest, and on the "
          "structure likewise (its residual counts the force (1 - "
          "alpha)/(2 beta) times; lumped mass): the interface then does no "
          "work besides the penalty's dissipation k |dg|^2 / 2, booked as "
          "the boundary's, and the force does not ring with the rule. The "
          "contact point of material-point contact then moves with the "
          "material point by default ('contact point motion'). Needs "
          "interface boundaries with 'condition = contact' or 'friction' "
          "and the penalty method. doc/theory.md, 'Contact force in "
          "time'.");
        AccelerationParameters::declare_parameters(prm);
        ConvergenceCriterion::declare_parameters(prm);
        InterfacePredictor::declare_parameters(prm);
      }
      prm.leave_subsection();
    }


    void
    CouplingParameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Coupling");
      scheme = (prm.get("scheme") == "weak" ? Scheme::weak : Scheme::strong);
      order  = (prm.get("order") == "structure first" ? Order::structure_first :
                                                        Order::MPM_first);
      {
        const std::string text = prm.get("Robin stiffness");
        robin_elastic          = text == "automatic";
        robin_inertia          = text == "inertia" || robin_elastic;
        if (!robin_inertia &&
            (!parse_double(text, robin_stiffness) || robin_stiffness < 0.))
          InputFile::reject("Coupling",
                            "Robin stiffness",
                            text,
                            "'automatic', 'inertia' or a number >= 0 "
                            "[Pa/m]");
        robin_depth = prm.get_double("Robin depth");
        if (!(robin_depth > 0.))
          InputFile::reject("Coupling",
                            "Robin depth",
                            prm.get("Robin depth"),
                            "a number > 0 [cells]");
      }
      {
        const std::string text = prm.get("Robin directions");
        robin_directions       = (text == "normal" ? RobinDirections::normal :
                                  text == "automatic" ? RobinDirections::automatic :
                                                        RobinDirections::all);
      }
      interface_stiffness_jacobian =
        prm.get("initial Jacobian") == "interface stiffness";
      if (interface_stiffness_jacobian && prm.get("acceleration") != "IQN-ILS")
        InputFile::reject("Coupling",
                          "initial Jacobian",
                          prm.get("initial Jacobian"),
                          "'none' (interface stiffness needs acceleration "
                          "= IQN-ILS; it is '" +
                            prm.get("acceleration") + "')");
      if (interface_stiffness_jacobian && prm.get("scheme") == "weak")
        InputFile::reject("Coupling",
                          "initial Jacobian",
                          prm.get("initial Jacobian"),
                          "'none' (interface stiffness needs scheme = "
                          "strong)");
      restart_at_contact_change = prm.get_bool("restart at contact change");
      warm_start                = prm.get_bool("warm start");
      interface_force_at_end =
        prm.get("interface force in time") == "end of step";
      acceleration.parse_parameters(prm, "Coupling");
      criterion.parse_parameters(prm, "Coupling");
      predictor.parse_parameters(prm);
      prm.leave_subsection();
    }


    WindowResult
    iterate_window(
      const std::function<void(const dealii::Vector<double> &,
                               dealii::Vector<double> &,
                               dealii::Vector<double> &)> &fixed_point,
      const dealii::Vector<double>                        &x0,
      InterfaceAccelerator                                &accelerator,
      ConvergenceCriterion                                &criterion,
      const bool                                           strong,
      const std::function<double()>                       &equilibrium_defect,
      const std::function<bool()>                         &active_set_changed)
    {
      WindowResult result;
      result.x = x0;
      result.x_tilde.reinit(x0.size());
      dealii::Vector<double> force;
      accelerator.start_window();
      criterion.start_window();
      // the last iterate whose evaluation succeeded (for the safeguard)
      dealii::Vector<double> good_x, good_x_tilde;
      while (true)
        {
          force.reinit(0);
          try
            {
              fixed_point(result.x, result.x_tilde, force);
            }
          catch (const EvaluationFailed &)
            {
              if (good_x.size() == 0 || result.restarts >= 2 ||
                  result.iterations + 1 >= criterion.maximum_iterations())
                throw;
              ++result.restarts;
              ++result.iterations;
              accelerator.reset();
              accelerator.start_window();
              result.x = accelerator.compute_next(good_x, good_x_tilde);
              continue;
            }
          good_x       = result.x;
          good_x_tilde = result.x_tilde;
          // another active set: the columns of the others describe another
          // operator (asked after every evaluation, so that the callback
          // can track the set from the window's first one on). At most
          // maximum_contact_restarts per window: each restart starts again
          // with a relaxation step, and where that step alone is unstable
          // (Dirichlet-Neumann without Robin springs) the set would switch
          // for ever (tests/coupling/contact_restart.cc)
          if (active_set_changed && active_set_changed() &&
              result.iterations > 0 &&
              result.contact_restarts < maximum_contact_restarts)
            {
              accelerator.reset();
              ++result.contact_restarts;
            }
          ++result.iterations;
          IterationRecord record;
          record.status = criterion.check(result.x,
                                          result.x_tilde,
                                          force.size() > 0 ? &force : nullptr);
          if (equilibrium_defect)
            {
              record.status.defect         = equilibrium_defect();
              record.status.defect_checked = true;
              if (!(record.status.defect <= criterion.relative_tolerance()))
                {
                  record.status.converged = false;
                  record.status.maximum_reached =
                    record.status.iterations >= criterion.maximum_iterations();
                }
            }
          const bool converged = record.status.converged;
          if (converged || !strong)
            {
              result.history.push_back(record);
              accelerator.end_window(result.x, result.x_tilde);
              result.accepted = true;
              return result;
            }
          if (record.status.maximum_reached)
            {
              result.history.push_back(record);
              return result;
            }
          result.x = accelerator.compute_next(result.x, result.x_tilde);
          record.acceleration = accelerator.info();
          result.history.push_back(record);
        }
    }
  } // namespace Coupling
} // namespace Talus
