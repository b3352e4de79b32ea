#include <talus/base/input.h>
#include <talus/mpm/mpm_problem.h>
#include <talus/mpm/state_transfer.h>

#include <deal.II/grid/grid_tools.h>

#include <boost/archive/archive_exception.hpp>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace Talus
{
  namespace MPM
  {
    template <int dim>
    MPMProblem<dim>::MPMProblem(const MPI_Comm       communicator,
                                const NewmarkBeta   &newmark,
                                dealii::TimerOutput &timer)
      : communicator(communicator)
      , newmark(newmark)
      , timer(timer)
    {}


    template <int dim>
    void
    MPMProblem<dim>::declare_parameters(dealii::ParameterHandler &prm,
                                        const unsigned int        n_boundaries)
    {
      BackgroundGrid<dim>::declare_parameters(prm);
      MaterialPoints<dim>::declare_parameters(prm);
      InitialStress<dim>::declare_parameters(prm);
      Materials::declare_parameters(prm);
      MPMSolver<dim>::declare_parameters(prm);
      Boundaries::BoundaryParticles<dim>::declare_parameters(prm, n_boundaries);
      LoadBalancing<dim>::declare_parameters(prm);
      AdaptiveGrid<dim>::declare_parameters(prm);
      MemoryEstimate<dim>::declare_parameters(prm);
      BodyContact::declare_parameters(prm);
    }


    template <int dim>
    void
    MPMProblem<dim>::parse_parameters(dealii::ParameterHandler &prm,
                                      const unsigned int        refinement)
    {
      // The model of every material subsection a body names; the points
      // carry as many history variables as the largest of them.
      const auto body_materials = MaterialPoints<dim>::body_materials(prm);
      materials.clear();
      materials.resize(Materials::max_materials);
      material_densities.assign(Materials::max_materials, 0.);
      unsigned int n_history = 0;
      for (const unsigned int m : body_materials)
        if (!materials[m])
          {
            materials[m] =
              Materials::create_model(prm, Materials::material_subsection(m));
            // the solver reads only the dim x dim x dim x dim block of dP/dF
            materials[m]->set_tangent_dimension(dim);
            n_history =
              std::max(n_history, materials[m]->n_history_variables());
          }
      constitutive_model = materials[body_materials[0]].get();

      // The memory of the grid and the points, estimated before they are
      // allocated: from the parameters for a box grid, from the coarse
      // cells of a Gmsh grid once it is read (before refinement and
      // points).
      prm.enter_subsection("Background grid");
      const bool box_grid = prm.get("type") == "box";
      prm.leave_subsection();
      if (box_grid)
        {
          memory.parse_parameters(prm, communicator, refinement, n_history);
          memory.check(prm);
        }
      // contact between bodies: one grid velocity field per body or one
      // for all (the grid's element depends on it)
      BodyContact body_contact;
      body_contact.parse_parameters(prm, body_materials.size());
      background_grid = std::make_unique<BackgroundGrid<dim>>(communicator);
      if (body_contact.multi_velocity_field)
        background_grid->set_velocity_fields(body_materials.size());
      background_grid->parse_parameters_and_create(prm);
      if (!box_grid)
        {
          const auto &tria = background_grid->triangulation;
          memory.parse_parameters(prm,
                                  communicator,
                                  refinement,
                                  n_history,
                                  tria.n_global_active_cells(),
                                  tria.n_vertices(),
                                  dealii::GridTools::volume(tria));
          memory.check(prm);
        }
      // the adaptive grid starts at its finest level (setup() coarsens)
      adaptive.parse_parameters(prm);
      adaptive.check_refined_boundaries(*background_grid);
      base_refinement = refinement;
      const unsigned int total_level =
        refinement + adaptive.initial_refinement();
      if (total_level > 0)
        {
          auto &grid = *background_grid;
          grid.triangulation.refine_global(total_level);
          grid.cell_extent /= std::pow(2., total_level);
          grid.cell_extent_level = total_level;
          grid.minimal_cell_diameter /= std::pow(2., total_level);
          grid.setup_dofs();
        }

      for (unsigned int m = 0; m < materials.size(); ++m)
        if (materials[m])
          {
            const std::string sub = Materials::material_subsection(m);
            prm.enter_subsection(sub);
            material_densities[m] = get_positive(prm, sub, "density");
            prm.leave_subsection();
          }
      material_density = material_densities[body_materials[0]];

      material_points = std::make_unique<MaterialPoints<dim>>(*background_grid);
      material_points->parse_parameters(prm);
      initial_stress_field.parse_parameters(prm);
      if (initial_stress_field.enabled())
        for (unsigned int b = 1; b < body_materials.size(); ++b)
          if (body_materials[b] != body_materials[0])
            InputFile::reject(MaterialPoints<dim>::body_subsection(b),
                              "material",
                              Materials::material_subsection(body_materials[b]),
                              "an initial stress (subsection Initial stress) "
                              "needs one material for all bodies");

      mpm_solver = std::make_unique<MPMSolver<dim>>(*background_grid,
                                                    *material_points,
                                                    *constitutive_model,
                                                    newmark,
                                                    timer);
      mpm_solver->parse_parameters(prm);
      mpm_solver->set_body_contact(body_contact);
      if (body_materials.size() > 1)
        {
          std::vector<const Materials::ConstitutiveModel *> models;
          for (const auto &m : materials)
            models.push_back(m.get());
          mpm_solver->set_materials(models);
        }

      boundary_particles =
        std::make_unique<Boundaries::BoundaryParticles<dim>>(*background_grid);
      boundary_particles->parse_parameters(prm);
      // with several velocity fields a boundary acts on each material
      // point through its own body's field: material-point contact;
      // the gap and stick state of a boundary particle are those of one
      // field
      if (body_contact.multi_velocity_field)
        for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
          if (!boundary_particles->boundary(b).material_point_contact)
            InputFile::reject(
              "Boundary particles/Boundary " + std::to_string(b + 1),
              "contact side",
              "boundary particles",
              "'material points' (with condition = contact or friction, "
              "method = penalty) when subsection Body contact sets "
              "'contact = multi-velocity field': the gap and stick state "
              "of a boundary particle belong to one velocity field; or use "
              "grid boundaries (fixed, slip, friction) or 'single velocity "
              "field'");
      balancing.parse_parameters(prm);
    }


    template <int dim>
    void
    MPMProblem<dim>::setup()
    {
      Assert(mpm_solver, dealii::ExcMessage("parse_parameters() first"));
      const auto &model = *constitutive_model;
      // contact data (material-point contact) for every boundary
      material_points->set_contact_slots(boundary_particles->n_boundaries());
      unsigned int n_history      = 0;
      double       p_wave_modulus = 0.;
      for (const auto &m : materials)
        if (m)
          {
            n_history      = std::max(n_history, m->n_history_variables());
            p_wave_modulus = std::max(p_wave_modulus, m->p_wave_modulus());
          }
      material_points->generate(
        material_densities,
        n_history,
        [&](const unsigned int m, const dealii::ArrayView<double> &h) {
          materials[m]->initialize_history(
            dealii::ArrayView<double>(h.data(),
                                      materials[m]->n_history_variables()));
        });
      initial_stress_field.apply(*material_points,
                                 model,
                                 mpm_solver->gravity(),
                                 communicator,
                                 mpm_solver->load_ramp());
      mpm_solver->setup();
      // the penalty of the boundaries from the stiffest material
      boundary_particles->generate(p_wave_modulus);
      mpm_solver->attach_boundary_particles(*boundary_particles);
      if (adaptive.enabled())
        {
          // penalty and augmented Lagrangian boundaries (on the grid side
          // or on the material points) read the grid through the
          // conforming values; the others use the uniform cell extent or a
          // multiplier space tied to the cells
          for (unsigned int b = 0; b < boundary_particles->n_boundaries(); ++b)
            {
              const auto       &desc = boundary_particles->boundary(b);
              const std::string sub =
                "Boundary particles/Boundary " + std::to_string(desc.slot + 1);
              if (desc.nitsche || desc.lagrange_multiplier)
                InputFile::reject(sub,
                                  "method",
                                  desc.method,
                                  "'penalty' or 'augmented Lagrangian' on an "
                                  "adaptive grid (subsection Adaptive grid, "
                                  "'enable = true'): " +
                                    desc.method +
                                    " is not implemented on a locally "
                                    "refined grid");
            }
          mpm_solver->check_local_refinement_support();
          // coarsen the empty cells of the uniform initial grid
          for (unsigned int pass = 0; pass < adaptive.initial_passes(); ++pass)
            if (!adapt_grid())
              break;
        }
    }


    template <int dim>
    bool
    MPMProblem<dim>::adapt_grid()
    {
      auto &grid = *background_grid;
      if (!adaptive.flag_cells(grid,
                               material_points->particle_handler(),
                               boundary_particles->particle_handler(),
                               base_refinement))
        return false;
      CommittedStateTransfer<dim> transfer(
        grid,
        *material_points,
        *boundary_particles,
        *mpm_solver,
        CommittedStateTransfer<dim>::Mode::repartition);
      transfer.prepare();
      grid.triangulation.execute_coarsening_and_refinement();
      transfer.unpack();
      saved_state_valid = false;
      return true;
    }


    template <int dim>
    void
    MPMProblem<dim>::initialize(const double time)
    {
      mpm_solver->initialize_acceleration(time);
    }


    template <int dim>
    void
    MPMProblem<dim>::prepare_step(const double new_time, const double dt)
    {
      step_end_time = new_time;
      mpm_solver->prepare_step(new_time, dt);
    }


    template <int dim>
    void
    MPMProblem<dim>::update_boundary_displacement()
    {
      mpm_solver->update_boundary_displacement();
    }


    template <int dim>
    NewtonResult
    MPMProblem<dim>::solve_step()
    {
      const NewtonResult result = mpm_solver->solve_step();
      // (the test of an exception inside a step, doc/debugging.md: a solve
      // of a step that ends after the given time throws, its trial state
      // left as the Newton iteration made it)
      if (const char *after = std::getenv("TALUS_DEBUG_THROW_AFTER_TIME"))
        if (step_end_time > std::atof(after))
          throw std::runtime_error(
            "TALUS_DEBUG_THROW_AFTER_TIME: an exception thrown on purpose "
            "after the Newton iteration of the step to t = " +
            std::to_string(step_end_time) + " s");
      return result;
    }


    template <int dim>
    void
    MPMProblem<dim>::commit_step()
    {
      mpm_solver->commit_step();
    }


    template <int dim>
    StepLosses<dim>
    MPMProblem<dim>::take_losses()
    {
      StepLosses<dim> l;
      l.region             = material_points->take_lost_region();
      l.n_points           = material_points->take_lost_count();
      l.mass               = material_points->take_lost_mass();
      l.boundary_particles = boundary_particles->take_lost_per_boundary();
      return l;
    }


    template <int dim>
    void
    MPMProblem<dim>::save_state()
    {
      material_points->save_state();
      boundary_particles->save_state();
      mpm_solver->save_state();
      saved_state_valid = true;
    }


    template <int dim>
    void
    MPMProblem<dim>::restore_state()
    {
      AssertThrow(saved_state_valid,
                  dealii::ExcMessage(
                    "MPMProblem::restore_state() without a save_state() on "
                    "the present partition of the grid (repartition() "
                    "discards the copy)"));
      material_points->restore_state();
      boundary_particles->restore_state();
      mpm_solver->restore_state();
    }


    namespace
    {
      /**
       * What identifies the MPM problem a checkpoint belongs to: written
       * first into `mpm_state`, compared with the problem built from the
       * parameter file before anything is loaded.
       */
      struct CheckpointIdentity
      {
        std::string         name                 = "talus-mpm-state";
        unsigned int        dimension            = 0;
        unsigned int        n_point_properties   = 0;
        unsigned int        n_history            = 0;
        unsigned int        n_contact_slots      = 0;
        unsigned int        n_boundaries         = 0;
        unsigned long long  n_coarse_cells       = 0;
        unsigned long long  n_active_cells       = 0;
        unsigned long long  n_points             = 0;
        unsigned long long  n_boundary_particles = 0;
        std::vector<double> grid_box;

        template <class Archive>
        void
        serialize(Archive &ar, const unsigned int /*version*/)
        {
          ar &name &dimension &n_point_properties &n_history &n_contact_slots
            &n_boundaries &n_coarse_cells &n_active_cells &n_points
              &n_boundary_particles &grid_box;
        }
      };
    } // namespace


    template <int dim>
    void
    MPMProblem<dim>::save_checkpoint(const std::string &directory)
    {
      auto &grid = *background_grid;

      CheckpointIdentity id;
      id.dimension = dim;
      id.n_point_properties =
        material_points->particle_handler().n_properties_per_particle();
      id.n_history       = material_points->n_history();
      id.n_contact_slots = material_points->n_contact_slots();
      id.n_boundaries    = boundary_particles->n_boundaries();
      id.n_coarse_cells  = grid.triangulation.n_cells(0);
      id.n_active_cells  = grid.triangulation.n_global_active_cells();
      id.n_points        = material_points->n_global_points();
      id.n_boundary_particles =
        boundary_particles->particle_handler().n_global_particles();
      for (unsigned int d = 0; d < dim; ++d)
        id.grid_box.push_back(grid.lower_corner[d]);
      for (unsigned int d = 0; d < dim; ++d)
        id.grid_box.push_back(grid.upper_corner[d]);

      // The grid vectors must live until the triangulation is saved.
      CommittedStateTransfer<dim> transfer(
        grid,
        *material_points,
        *boundary_particles,
        *mpm_solver,
        CommittedStateTransfer<dim>::Mode::serialization);
      transfer.prepare();
      grid.triangulation.save(directory + "/mpm_grid");

      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          std::ofstream out(directory + "/mpm_state", std::ios::binary);
          boost::archive::binary_oarchive archive(out);
          archive << id;
          mpm_solver->serialize_committed_scalars(archive);
        }
    }


    template <int dim>
    void
    MPMProblem<dim>::load_checkpoint(const std::string &directory)
    {
      auto             &grid       = *background_grid;
      const std::string state_file = directory + "/mpm_state";
      const auto        reject     = [&](const std::string &what) {
        throw ExcInvalidInput("Cannot resume from the checkpoint <" +
                              directory + ">: " + what);
      };

      // First check that the checkpoint belongs to this problem.
      CheckpointIdentity id;
      {
        std::ifstream in(state_file, std::ios::binary);
        if (!in)
          reject("the file <" + state_file + "> cannot be read.");
        try
          {
            boost::archive::binary_iarchive archive(in);
            archive >> id;
            if (id.name != CheckpointIdentity().name)
              reject("the file <" + state_file +
                     "> is not the MPM state of a Talus checkpoint.");
            mpm_solver->serialize_committed_scalars(archive);
          }
        catch (const boost::archive::archive_exception &e)
          {
            reject("the file <" + state_file +
                   "> is not a readable MPM state (" + e.what() + ").");
          }
      }
      const auto mismatch = [&](const std::string       &what,
                                const unsigned long long stored,
                                const unsigned long long here,
                                const std::string       &hint) {
        if (stored != here)
          reject("it was written for " + what + " " + std::to_string(stored) +
                 ", the parameter file gives " + std::to_string(here) + " (" +
                 hint + ").");
      };
      mismatch("dimension", id.dimension, dim, "'dimension'");
      mismatch("a background grid of coarse cells",
               id.n_coarse_cells,
               grid.triangulation.n_cells(0),
               "subsection <Background grid>; checkpoints of refined levels "
               "of a convergence study cannot be resumed");
      mismatch("material points with history variables",
               id.n_history,
               material_points->n_history(),
               "the constitutive model of subsection <Material>");
      mismatch("boundaries",
               id.n_boundaries,
               boundary_particles->n_boundaries(),
               "subsection <Boundary particles>");
      mismatch("material points with properties",
               id.n_point_properties,
               material_points->particle_handler().n_properties_per_particle(),
               "subsections <Material>, <Body> (number of bodies) and "
               "<Boundary particles>");
      for (unsigned int d = 0; d < dim && id.grid_box.size() == 2 * dim; ++d)
        if (std::abs(id.grid_box[d] - grid.lower_corner[d]) >
              1e-12 * grid.minimal_cell_diameter ||
            std::abs(id.grid_box[dim + d] - grid.upper_corner[d]) >
              1e-12 * grid.minimal_cell_diameter)
          reject("it was written for another background grid (bounding box) "
                 "than subsection <Background grid> describes.");

      // The grid with the particles and the grid vectors on it, and
      // everything that depends on the partition of the grid.
      grid.triangulation.load(directory + "/mpm_grid");
      CommittedStateTransfer<dim>(
        grid,
        *material_points,
        *boundary_particles,
        *mpm_solver,
        CommittedStateTransfer<dim>::Mode::serialization)
        .unpack();
      saved_state_valid = false;

      if (material_points->n_global_points() != id.n_points ||
          boundary_particles->particle_handler().n_global_particles() !=
            id.n_boundary_particles)
        reject("it holds " +
               std::to_string(material_points->n_global_points()) +
               " material points and " +
               std::to_string(
                 boundary_particles->particle_handler().n_global_particles()) +
               " boundary particles after loading, its state file says " +
               std::to_string(id.n_points) + " and " +
               std::to_string(id.n_boundary_particles) + ".");
    }


    template <int dim>
    void
    MPMProblem<dim>::repartition()
    {
      auto &grid = *background_grid;
      // the weights only for this call: nothing else repartitions the grid
      const boost::signals2::scoped_connection weight =
        grid.triangulation.signals.weight.connect(
          [&](const typename dealii::parallel::distributed::Triangulation<
                dim>::cell_iterator                                &cell,
              const typename dealii::Triangulation<dim>::CellStatus status) {
            return balancing.cell_weight(
              cell,
              status,
              material_points->particle_handler(),
              boundary_particles->particle_handler());
          });
      CommittedStateTransfer<dim> transfer(
        grid,
        *material_points,
        *boundary_particles,
        *mpm_solver,
        CommittedStateTransfer<dim>::Mode::repartition);
      transfer.prepare();
      grid.triangulation.repartition();
      transfer.unpack();
      saved_state_valid = false;
    }


    template <int dim>
    RepartitionRecord
    MPMProblem<dim>::balance_load(const unsigned int                step,
                                  const dealii::ConditionalOStream &log)
    {
      RepartitionRecord record;
      if (adaptive.due(step))
        {
          dealii::TimerOutput::Scope scope(timer, "adaptive grid");
          record.adapted = adapt_grid();
          if (record.adapted)
            log << "  adaptive grid at step " << step << ": "
                << background_grid->triangulation.n_global_active_cells()
                << " cells, " << background_grid->dof_handler.n_dofs()
                << " DoFs\n";
        }
      if (!balancing.enabled())
        return record;
      const auto &handler = material_points->particle_handler();
      record.imbalance_before =
        LoadBalancing<dim>::imbalance(handler, communicator);
      record.imbalance_after = record.imbalance_before;
      if (!balancing.due(step, record.imbalance_before))
        return record;
      dealii::TimerOutput::Scope scope(timer, "load balancing");
      repartition();
      record.repartitioned = true;
      record.imbalance_after =
        LoadBalancing<dim>::imbalance(handler, communicator);
      balancing.record_repartition(record.imbalance_after);
      const unsigned long long local = handler.n_locally_owned_particles();
      record.max_points = dealii::Utilities::MPI::max(local, communicator);
      record.min_points = dealii::Utilities::MPI::min(local, communicator);
      log << "  load balancing at step " << step
          << ": repartitioned, imbalance of the material points (largest "
             "rank / mean) "
          << std::setprecision(4) << record.imbalance_before << " -> "
          << record.imbalance_after << std::defaultfloat << " (points per rank "
          << record.min_points << " to " << record.max_points << ")\n";
      return record;
    }


    template <int dim>
    void
    MPMProblem<dim>::print_adaptive_grid(
      const dealii::ConditionalOStream &out) const
    {
      if (!adaptive.enabled())
        return;
      const auto &grid = *background_grid;
      if (boundary_particles->n_boundaries() > 0)
        {
          const auto cells = adaptive.boundary_cells_at_maximum_level(
            grid, boundary_particles->particle_handler(), base_refinement);
          out << "  adaptive grid: "
              << grid.triangulation.n_global_active_cells() << " cells, "
              << grid.dof_handler.n_dofs() << " DoFs; " << cells.first
              << " cells hold boundary particles, " << cells.second
              << " of them at the maximum level " << adaptive.maximum_level()
              << '\n';
        }
      if (!adaptive.refined_boundaries().empty())
        {
          const auto cells = adaptive.boundary_face_cells_at_maximum_level(
            grid,
            material_points->particle_handler(),
            boundary_particles->particle_handler(),
            base_refinement);
          std::string ids;
          for (const auto id : adaptive.refined_boundaries())
            ids += (ids.empty() ? "" : ", ") + std::to_string(id);
          out << "  adaptive grid: "
              << grid.triangulation.n_global_active_cells() << " cells, "
              << grid.dof_handler.n_dofs() << " DoFs; " << cells.first
              << " cells at the faces of boundaries " << ids
              << " are near the material, " << cells.second
              << " of them at the maximum level " << adaptive.maximum_level()
              << '\n';
        }
    }


    template <int dim>
    void
    MPMProblem<dim>::print_summary(const dealii::ConditionalOStream &out) const
    {
      const auto &grid       = *background_grid;
      const auto &boundaries = *boundary_particles;
      out << "  background grid: " << grid.triangulation.n_global_active_cells()
          << " cells, " << grid.dof_handler.n_dofs() << " DoFs\n"
          << "  material points: " << material_points->n_global_points() << '\n'
          << "  material: " << constitutive_model->name() << ", density "
          << material_density << " kg/m^3\n";
      if (material_points->n_bodies() > 1)
        {
          std::vector<unsigned long long> count(material_points->n_bodies(), 0);
          for (const auto &p : material_points->particle_handler())
            ++count[material_points->body_of(p.get_properties())];
          for (auto &c : count)
            c = dealii::Utilities::MPI::sum(c, communicator);
          for (unsigned int b = 0; b < count.size(); ++b)
            {
              const unsigned int m = material_points->body_material(b);
              out << "  body " << b + 1 << ": " << count[b]
                  << " material points, " << Materials::material_subsection(m)
                  << " (" << materials[m]->name() << ", density "
                  << material_densities[m] << " kg/m^3)\n";
            }
        }
      if (initial_stress_field.enabled())
        out << "  initial stress: " << initial_stress_field.description()
            << '\n';
      print_adaptive_grid(out);
      if (mpm_solver->ghost_penalty() > 0.)
        out << "  ghost penalty: factor " << mpm_solver->ghost_penalty()
            << " (gamma = factor * P-wave modulus), on the faces of cut "
               "cells\n";
      if (boundaries.empty())
        return;
      std::vector<unsigned int> count(boundaries.n_boundaries(), 0);
      for (const auto &p : boundaries.particle_handler())
        ++count[static_cast<unsigned int>(
          p.get_properties()
            [Boundaries::BoundaryParticleProperties<dim>::boundary])];
      MPI_Allreduce(MPI_IN_PLACE,
                    count.data(),
                    count.size(),
                    MPI_UNSIGNED,
                    MPI_SUM,
                    communicator);
      const auto number = [](const double x) {
        std::ostringstream o;
        o << x;
        return o.str();
      };
      for (unsigned int b = 0; b < boundaries.n_boundaries(); ++b)
        {
          const auto &desc = boundaries.boundary(b);
          out << "  boundary " << desc.name << ": " << desc.geometry << ", "
              << count[b] << " boundary particles, "
              << (desc.condition == Boundaries::Condition::fixed ?
                    "fixed" :
                  desc.condition == Boundaries::Condition::slip ?
                    "slip" :
                  desc.condition == Boundaries::Condition::contact ?
                    "contact" :
                    "friction mu = " + number(desc.friction_coefficient))
              << (desc.augmented ?
                    ", augmented Lagrangian, penalty" :
                  desc.lagrange_multiplier ?
                    ", Lagrange multipliers, trial-force" :
                  desc.nitsche ?
                    ", Nitsche (theta = " + number(desc.nitsche_theta) +
                      "), stabilisation" :
                    ", penalty")
              << " beta = " << std::setprecision(4) << desc.beta << " Pa/m"
              << std::defaultfloat << '\n';
        }
    }


    template class MPMProblem<2>;
    template class MPMProblem<3>;
  } // namespace MPM
} // namespace Talus
