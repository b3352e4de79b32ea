#ifndef talus_coupling_structure_interface_h
#define talus_coupling_structure_interface_h

#include <talus/boundaries/boundary_particles.h>
#include <talus/coupling/interface_transfer.h>
#include <talus/structure/structure.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/vector.h>

#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace Talus
{
  namespace Coupling
  {
    /**
     * The interface between the barrier structure and the MPM (founding
     * paper, section 4; deal.II step-70): one mesh of the structure (a
     * membrane's Triangulation<2,3> in 3D, a string's line mesh in the
     * plane z = 0 in 2D, or the boundary of a continuum solid, all of it or
     * its faces of `structure boundary ids`, of degree 1) becomes the
     * surface of one or more MPM boundaries with `geometry = external`,
     * whose boundary particles are the Gauss points of that surface.
     *
     * The surface is a Triangulation<dim-1, dim> in the MPM's space: the
     * mesh's vertices with their (x, y) in 2D (the structure of a 2D
     * problem lies in the plane z = 0), as they are in 3D. On it lives
     * FESystem(FE_Q(1), dim); each of its vertex DoFs is a DoF of the
     * structure node at that vertex (found once). With InterfaceTransfer on
     * that surface, per boundary particle p at its reference position X_p
     * (located once, never searched again),
     *
     *   u_p = sum_i N_i(X_p) U_i          (consistent displacement)
     *   F_i = sum_p N_i(X_p) f_p          (conservative force)
     *
     * so sum_i F_i = sum_p f_p and U . F = sum_p u_p . f_p to round-off.
     * The MPM reads u(X, t) through BoundaryParticles::set_displacement():
     * the committed displacement at the start of the step and the trial one
     * at its end, linear in between (the boundary's velocity over the step
     * is the constant (u_end - u_start)/dt).
     *
     * Several boundaries may share the surface: the two faces of a net (one
     * with `flip normals`), each a contact boundary, so that the material
     * can hit either face; their forces add up.
     *
     * MPI: the structure is replicated; every rank holds the transfer of
     * every interface point (gathered once after the particles were made)
     * and sums its own particles' reactions, which one MPI_Allreduce of the
     * structure's force vector adds over the ranks.
     *
     * Parameters: subsection `Coupling/Interface`.
     */
    template <int dim>
    class StructureInterface
    {
    public:
      /** Declare `structure mesh`, `boundaries` and `structure boundary
       * ids` in the current subsection (the coupling enters
       * `Coupling/Interface`). */
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /** Parse them from the current subsection. */
      void
      parse_parameters(dealii::ParameterHandler &prm);

      /**
       * Build the surface from the mesh `structure mesh` of @p structure
       * (after Structure::setup_dofs()), map its vertices to the
       * structure's nodes and hand it to every boundary named in
       * `boundaries` (BoundaryParticles::set_surface() and
       * set_displacement()). Call it after the boundaries were parsed and
       * before BoundaryParticles::generate(). Errors (ExcInvalidInput) name
       * the parameter: a mesh that is not part of the structure, a
       * boundary that does not exist or is not `geometry = external`, a
       * mesh that cannot be an interface in @p dim dimensions.
       */
      void
      attach(const Structure::Structure         &structure,
             Boundaries::BoundaryParticles<dim> &boundaries);

      /**
       * After the boundary particles were generated: gather every
       * interface particle (all ranks) and locate it on the surface. A
       * boundary without particles, or one that lost particles because
       * the surface leaves the background grid, is an error.
       */
      void
      setup(const Boundaries::BoundaryParticles<dim> &boundaries,
            const MPI_Comm                            communicator);

      /**
       * The displacement the MPM sees during the step from @p t_start to
       * @p t_end: @p U_start at t_start, @p U_end at t_end (structure DoF
       * vectors), linear in between, constant outside.
       */
      void
      set_step_displacement(const dealii::Vector<double> &U_start,
                            const dealii::Vector<double> &U_end,
                            const double                  t_start,
                            const double                  t_end);

      /**
       * The interface force on the structure [N per structure DoF]: the
       * reactions @p reactions of this rank's boundary particles (by
       * particle index, MPM::MPMSolver::boundary_reactions()) distributed
       * with the transfer, summed over all ranks (collective). Reactions
       * of particles of other boundaries are ignored.
       */
      dealii::Vector<double>
      structure_forces(
        const std::vector<std::pair<dealii::types::particle_index,
                                    dealii::Tensor<1, dim>>> &reactions,
        const unsigned int                                    n_dofs,
        const MPI_Comm communicator) const;

      /**
       * The interface area of each structure DoF covered by the particles
       * listed in @p reactions that carry a force (nonzero reaction),
       * sum_p N_i(X_p) w_p [m^2 in 3D, m in 2D], summed over all ranks
       * (collective): the lumped weight of Robin interface springs. With
       * @p normal_only each component d of a point's weight is scaled by
       * n_d^2, n the direction of its reaction summed over the ranks (the
       * boundary's normal for slip and frictionless contact): the diagonal
       * of the weight times n n^T, so that no spring acts along the
       * interface where the material transmits no tangential force.
       */
      dealii::Vector<double>
      covered_area(
        const std::vector<std::pair<dealii::types::particle_index,
                                    dealii::Tensor<1, dim>>> &reactions,
        const unsigned int                                    n_dofs,
        const MPI_Comm                                        communicator,
        const bool normal_only = false) const;

      /** Which interface points carried a force in the last
       * structure_forces() (all ranks; order of the points): the active
       * set of a contact interface. */
      std::vector<bool>
      loaded_points() const;

      /** The summed point force of the last structure_forces() [N]. */
      const dealii::Tensor<1, dim> &
      total_particle_force() const
      {
        return last_total_force;
      }

      /** The displacement of every interface point for the structure
       * displacement @p U (order of the points) [m]. */
      std::vector<dealii::Tensor<1, dim>>
      point_displacements(const dealii::Vector<double> &U) const;

      /** Number of interface points (boundary particles, all ranks). */
      unsigned int
      n_points() const
      {
        return transfer.n_points();
      }

      /** Name of the structure mesh. */
      const std::string &
      mesh_name() const
      {
        return mesh;
      }

      /** The MPM boundaries of the interface (indices). */
      const std::vector<unsigned int> &
      boundary_indices() const
      {
        return boundary_ids;
      }

      /** Local surface DoF -> structure DoF. */
      dealii::types::global_dof_index
      structure_dof(const unsigned int i) const
      {
        return structure_dofs[i];
      }

      /** The structure DoFs of the interface surface (sorted, unique). */
      std::vector<dealii::types::global_dof_index>
      interface_structure_dofs() const;

      /** The point of the interface particle with index @p id
       * (numbers::invalid_unsigned_int if it is none). */
      unsigned int
      point_of(const dealii::types::particle_index id) const;

      /**
       * The nodal structure vectors (length @p n_dofs) of point-force
       * changes listed by particle index, one list per column (this rank's
       * entries, e.g. MPM::MPMSolver::linearised_boundary_reactions()),
       * summed over the ranks in one reduction (collective). Unlike
       * structure_forces() it leaves the last forces as they are.
       */
      std::vector<dealii::Vector<double>>
      linearised_structure_forces(
        const std::vector<std::vector<
          std::pair<dealii::types::particle_index, dealii::Tensor<1, dim>>>>
                          &columns,
        const unsigned int n_dofs,
        const MPI_Comm     communicator) const;

      /** Interface work U . F of the structure's vectors and sum_p u_p .
       * f_p of the points for the last structure_forces() [J] (equal to
       * round-off: the transfer is conservative). */
      std::pair<double, double>
      interface_work(const dealii::Vector<double> &U,
                     const dealii::Vector<double> &F) const;

    private:
      std::string               mesh;
      std::vector<std::string>  boundary_names;
      std::vector<unsigned int> boundary_ids;
      /** `structure boundary ids`: the faces of a solid that form the
       * interface (empty: its whole boundary). */
      std::set<dealii::types::boundary_id> structure_boundary_ids;

      /** `structure boundary ids` as a comma-separated list. */
      std::string
      ids_text() const;

      /** The interface surface in the MPM's space. */
      dealii::Triangulation<dim - 1, dim> surface;
      dealii::FESystem<dim - 1, dim>   fe{dealii::FE_Q<dim - 1, dim>(1), dim};
      dealii::DoFHandler<dim - 1, dim> dof_handler;
      std::vector<dealii::types::global_dof_index> structure_dofs;
      InterfaceTransfer<dim - 1, dim>              transfer;

      /** Surface measure of every point [m^2 in 3D, m in 2D]. */
      std::vector<double> point_weights;

      /** Nodal vector (structure DoFs) of the point vectors @p f. */
      dealii::Vector<double>
      to_structure(const std::vector<dealii::Tensor<1, dim>> &f,
                   const unsigned int                         n_dofs) const;

      /** Point index by particle index, and by reference position. */
      std::map<dealii::types::particle_index, unsigned int> point_of_particle;
      std::map<std::vector<double>, unsigned int>           point_of_position;

      /** Displacements of the points at the start and end of the step. */
      std::vector<dealii::Tensor<1, dim>> u_start, u_end;
      double                              t_start = 0., t_end = 0.;

      /** Point forces of the last structure_forces() (all ranks). */
      mutable std::vector<dealii::Tensor<1, dim>> last_point_forces;
      mutable dealii::Tensor<1, dim>              last_total_force;

      /** u(X, t) of the boundary particle at @p X. */
      dealii::Tensor<1, dim>
      displacement_at(const dealii::Point<dim> &X, const double t) const;
    };
  } // namespace Coupling
} // namespace Talus

#endif
