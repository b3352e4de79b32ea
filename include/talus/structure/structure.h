#ifndef talus_structure_structure_h
#define talus_structure_structure_h

#include <talus/structure/continuum_solid.h>
#include <talus/structure/line_elements.h>
#include <talus/structure/membrane.h>
#include <talus/structure/sliding_cable.h>

#include <deal.II/base/point.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace Structure
  {
    /**
     * A line mesh (Triangulation<1,3>, serial): either every cell is one
     * two-node element (truss, cable, brake), or the whole mesh is one
     * sliding cable through its vertices.
     */
    struct LineMesh
    {
      std::string                         name;
      dealii::Triangulation<1, 3>         triangulation;
      dealii::DoFHandler<1, 3>            dof_handler;
      std::shared_ptr<const LineElement>  element;
      std::shared_ptr<const SlidingCable> sliding_cable;
      dealii::types::global_dof_index     offset = 0;
      /** Committed and trial history, by active cell index. */
      std::vector<LineState> state, trial_state;
      /** Axial force of each cell after the last assembly [N]. */
      std::vector<double> force;
      /** Sliding cable: global dofs of the nodes in cable order. */
      std::vector<std::array<dealii::types::global_dof_index, 3>> chain;
      std::vector<dealii::Tensor<1, 3>>                           chain_X;
      /** Sliding cable: active cell index of each segment in cable order. */
      std::vector<unsigned int> chain_cells;
    };


    /** A membrane mesh (Triangulation<2,3>, serial). */
    struct MembraneMesh
    {
      std::string                     name;
      dealii::Triangulation<2, 3>     triangulation;
      dealii::DoFHandler<2, 3>        dof_handler;
      std::shared_ptr<const Membrane> membrane;
      dealii::types::global_dof_index offset = 0;
      /** Stress results per active cell after the last assembly. */
      std::vector<MembraneCellOutput> cell_output;
    };


    /**
     * A continuum solid mesh (serial) with FESystem(FE_Q(degree),3), one
     * ContinuumSolid<dim>, and dead tractions on boundary ids (scaled by
     * the load factor). dim = 3: a Triangulation<3,3>. dim = 2: a
     * plane-strain solid of a 2D problem, the Triangulation<2,2> of the
     * x-y plane embedded as Triangulation<2,3> at z = 0 (as the 2D string),
     * u_z = 0 on all its DoFs, forces and masses of a slice of thickness
     * @p thickness.
     */
    template <int dim>
    struct SolidMeshT
    {
      static constexpr int                       dimension = dim;
      std::string                                name;
      dealii::Triangulation<dim, 3>              triangulation;
      dealii::DoFHandler<dim, 3>                 dof_handler;
      std::shared_ptr<const ContinuumSolid<dim>> solid;
      std::unique_ptr<dealii::FESystem<dim, 3>>  fe;
      dealii::types::global_dof_index            offset = 0;
      std::vector<std::pair<unsigned int, dealii::Tensor<1, 3>>> tractions;
      /** Out-of-plane thickness t of a plane-strain solid (dim = 2) [m];
       * 1 for dim = 3. */
      double thickness = 1.;
      /** Results per active cell after the last assembly. */
      std::vector<SolidCellOutput> cell_output;
    };

    /** A three-dimensional solid mesh. */
    using SolidMesh = SolidMeshT<3>;
    /** A plane-strain solid mesh of a 2D problem. */
    using PlaneSolidMesh = SolidMeshT<2>;


    /**
     * A part of the structure: the DoFs connected through cells (elements)
     * and ties (Structure::parts()).
     */
    struct StructurePart
    {
      std::vector<std::string> meshes; ///< names of its meshes
      unsigned int             n_nodes = 0;
      dealii::Point<3>         a_node; ///< position of one of its nodes [m]
      /** Direction d has a prescribed DoF in the part; if not, the
       * translation along d is a zero-energy mode of the stiffness. */
      std::array<bool, 3> held = {{false, false, false}};
      double              mass = 0.; ///< lumped, one direction [kg]
      /**
       * A rigid motion with a rotation moves nodes of the part but no
       * prescribed DoF (the supports lie at one point or on one line, the
       * rotation axis): the rank of the six rigid-body modes evaluated at
       * the prescribed DoFs is smaller than at all the part's nodes. Only
       * meaningful when the part is held in x, y and z.
       */
      bool can_rotate = false;
      /** Axis of that rotation (unit) and a point on it [m]. */
      dealii::Tensor<1, 3> rotation_axis;
      dealii::Point<3>     axis_point;
      /** The part has a continuum solid or a membrane mesh (elements that
       * resist in-plane shear, unlike cables and trusses). */
      bool has_continuum = false;
      /** All prescribed DoFs of the part are at one point. */
      bool held_at_one_point = false;
    };


    /**
     * The structural model: several deal.II meshes (membranes on
     * Triangulation<2,3>, trusses, cables, brakes and sliding cables on
     * Triangulation<1,3>, each with FESystem(FE_Q(1),3), and continuum
     * solids on Triangulation<3,3> with FESystem(FE_Q(p),3)), their degrees of
     * freedom in one global numbering (the DoFs of mesh m follow those of
     * mesh m-1), vertices that coincide across meshes tied by
     * AffineConstraints (shackles, post heads, cable ends), supports as
     * homogeneous or prescribed (displacement-controlled) Dirichlet
     * conditions, and the loads: gravity, point loads, follower pressure
     * and external nodal forces set from outside (the coupling).
     *
     * Use: add meshes and fill their triangulations, setup_dofs(), then add
     * supports and loads by node, setup_system(); then assemble() at any
     * displacement. History is committed by commit_state().
     */
    class Structure
    {
    public:
      /** Add a mesh; fill its triangulation before setup_dofs(). */
      LineMesh &
      add_line_mesh(const std::string                        &name,
                    const std::shared_ptr<const LineElement> &element);

      LineMesh &
      add_sliding_cable(const std::string                         &name,
                        const std::shared_ptr<const SlidingCable> &cable);

      MembraneMesh &
      add_membrane(const std::string                     &name,
                   const std::shared_ptr<const Membrane> &membrane);

      /** A continuum solid; fill its triangulation before setup_dofs(). */
      SolidMesh &
      add_solid(const std::string                              &name,
                const std::shared_ptr<const ContinuumSolid<3>> &solid);

      /**
       * A plane-strain solid of a 2D problem: @p plane (cells in the x-y
       * plane) is copied to the mesh's Triangulation<2,3> at z = 0; the
       * element is @p solid per unit thickness times @p thickness [m].
       * setup_dofs() fixes u_z of all its DoFs.
       */
      PlaneSolidMesh &
      add_plane_solid(const std::string                              &name,
                      const std::shared_ptr<const ContinuumSolid<2>> &solid,
                      const double                                    thickness,
                      const dealii::Triangulation<2>                 &plane);

      /**
       * Distribute the DoFs of every mesh, number them globally and find
       * the nodes: vertices closer than @p tolerance (relative to the size of
       * the structure) are one node, the DoFs of all but the first are tied
       * to it.
       */
      void
      setup_dofs(const double tolerance = 1e-8);

      /** Index of the node at @p p (within @p tolerance [m]), or
       * numbers::invalid_unsigned_int. */
      unsigned int
      find_node(const dealii::Point<3> &p, const double tolerance) const;

      /** Nodes whose position satisfies @p predicate. */
      std::vector<unsigned int>
      find_nodes(
        const std::function<bool(const dealii::Point<3> &)> &predicate) const;

      unsigned int
      n_nodes() const;

      const dealii::Point<3> &
      node_position(const unsigned int node) const;

      /** The (master) global DoF of component @p c of node @p node. */
      dealii::types::global_dof_index
      node_dof(const unsigned int node, const unsigned int c) const;

      /**
       * Fix component @p c of @p node at displacement @p value times the
       * load factor (0: a support).
       */
      void
      prescribe(const unsigned int node,
                const unsigned int c,
                const double       value = 0.);

      /**
       * Fix global DoF @p dof (of any mesh; a tied DoF is replaced by its
       * master) at @p value times the load factor.
       */
      void
      prescribe_dof(const dealii::types::global_dof_index dof,
                    const double                          value = 0.);

      /**
       * Fix the components @p components (x, y, z) of every DoF of solid
       * mesh @p mesh on the faces with boundary id @p boundary_id. Returns
       * the number of DoFs fixed.
       */
      unsigned int
      prescribe_solid_boundary(const unsigned int       mesh,
                               const unsigned int       boundary_id,
                               const std::vector<bool> &components = {true,
                                                                      true,
                                                                      true});

      /**
       * Fix the components @p components of every DoF of solid mesh
       * @p mesh whose support point lies in the box [@p lower, @p upper]
       * (with a tolerance of 1e-10 of the mesh size). Returns the number of
       * DoFs fixed.
       */
      unsigned int
      prescribe_solid_box(const unsigned int       mesh,
                          const dealii::Point<3>  &lower,
                          const dealii::Point<3>  &upper,
                          const std::vector<bool> &components);

      /** As prescribe_solid_boundary() and prescribe_solid_box() for the
       * solid @p mesh of any dimension (a SolidMesh or PlaneSolidMesh of
       * this structure). */
      template <int dim>
      unsigned int
      prescribe_solid_boundary(const SolidMeshT<dim>   &mesh,
                               const unsigned int       boundary_id,
                               const std::vector<bool> &components = {true,
                                                                      true,
                                                                      true});

      template <int dim>
      unsigned int
      prescribe_solid_box(const SolidMeshT<dim>   &mesh,
                          const dealii::Point<3>  &lower,
                          const dealii::Point<3>  &upper,
                          const std::vector<bool> &components);

      /**
       * The connected parts of the structure (after setup_system()): DoFs
       * joined by a cell of any mesh or by a tie, with their meshes, a node
       * position, the directions in which a DoF is prescribed and their
       * mass. A part with no prescribed DoF along a direction can
       * translate freely along it (every element is invariant under
       * translations): its static stiffness is singular; with no
       * prescribed DoF at all it is connected to nothing.
       */
      std::vector<StructurePart>
      parts() const;

      /** Remove the condition of prescribe() (call setup_system() again,
       * which keeps nothing but the constraints and the matrix pattern). */
      void
      release(const unsigned int node, const unsigned int c);

      /** Point load [N] at a node, scaled by the load factor. */
      void
      add_point_load(const unsigned int node, const dealii::Tensor<1, 3> &F);

      /** Gravity acceleration [m/s^2], scaled by the load factor if
       * scale_gravity. */
      dealii::Tensor<1, 3> gravity;

      /** Scale gravity by the load factor (false: the self weight acts in
       * full from load factor 0 on, e.g. during the form finding of a
       * barrier, and the load factor scales the other loads only). */
      bool scale_gravity = true;

      /** External nodal forces [N] per global DoF, not scaled by the load
       * factor (set from outside each step, e.g. by the coupling). */
      dealii::Vector<double> external_forces;

      /**
       * Interface springs of a Robin coupling [N/m] per global DoF
       * (default empty: none): assemble() adds the force
       * k_i (u_i - a_i) towards the anchor a = interface_anchor and k_i
       * to the tangent. Set by the coupling for one time window; they
       * vanish at its converged state (u = a there), so they change how
       * the coupling iterates, not its result
       * (Coupling::GaussSeidelCoupling).
       */
      dealii::Vector<double> interface_springs, interface_anchor;

      /** Constraints, sparsity, matrix and vectors. */
      void
      setup_system();

      /**
       * Residual r = f_int(u) - f_ext (condensed: zero on constrained DoFs)
       * and, if @p K is given, its tangent. Updates the trial history and
       * the element results. Returns the norm of r.
       */
      double
      assemble(const dealii::Vector<double> &u,
               const double                  load_factor,
               dealii::Vector<double>       &r,
               dealii::SparseMatrix<double> *K);

      /** Set the prescribed DoFs of @p u for @p load_factor and make the
       * tied DoFs equal to their masters. */
      void
      apply_prescribed(dealii::Vector<double> &u,
                       const double            load_factor) const;

      /** Elastic energy stored in all elements at the last assemble() [J]
       * (membranes: the SVK energy, also where wrinkling modifies the
       * stress; brakes: the energy of their elastic spring; sliding
       * cables: that of their uniform strain, 0 with friction, which
       * dissipates). */
      double
      strain_energy() const;

      /** Energy dissipated by the elements up to the committed history
       * [J]: brake strokes and truss plasticity (LineElement::
       * dissipated_energy()); not the friction of sliding cables. */
      double
      dissipated_energy() const;

      /**
       * Lumped mass per DoF [kg] (rho A L/2 per node of a line element,
       * rho t int N_I dA0 for membranes, rho int N_I dV0 for solids),
       * summed onto the master DoF of
       * each node; zero on tied DoFs.
       */
      const dealii::Vector<double> &
      lumped_mass() const;

      /**
       * Consistent mass matrix (condensed with the constraints; sparsity of
       * setup_system()): rho A L/6 [[2,1],[1,2]] per component for line
       * elements, the lumped masses for sliding cables, rho t int N_I N_J
       * dA0 for membranes, rho int N_I N_J dV0 for solids [kg].
       */
      void
      assemble_consistent_mass(dealii::SparseMatrix<double> &M) const;

      /** Potential of the loads at load factor @p load_factor: -(point
       * loads + gravity + external nodal forces) . u [J]. */
      double
      load_potential(const dealii::Vector<double> &u,
                     const double                  load_factor) const;

      /** Accept the trial history (end of a converged step). */
      void
      commit_state();

      /**
       * Force [N] the structure exerts on the supports at @p node
       * (f_int - f_ext summed over the DoFs of the node) after the last
       * assemble().
       */
      dealii::Tensor<1, 3>
      reaction(const unsigned int node) const;

      /** Displacement of @p node in @p u. */
      dealii::Tensor<1, 3>
      node_displacement(const dealii::Vector<double> &u,
                        const unsigned int            node) const;

      /** @name Coupling interface
       * What a partitioned coupling (e.g. the MPM) uses each time step:
       * the nodes of a mesh (the net), their current positions, and the
       * external nodal forces it sets before DynamicSolver::solve_step().
       * @{ */

      /** Current position X + u of @p node [m]. */
      dealii::Point<3>
      node_current_position(const dealii::Vector<double> &u,
                            const unsigned int            node) const;

      /**
       * Node of every vertex of membrane mesh @p mesh (index into
       * membrane_meshes), indexed by the vertex index of its
       * triangulation (numbers::invalid_unsigned_int for unused vertices).
       * Valid after setup_dofs().
       */
      std::vector<unsigned int>
      membrane_vertex_nodes(const unsigned int mesh) const;

      /** As membrane_vertex_nodes() for line mesh @p mesh. */
      std::vector<unsigned int>
      line_vertex_nodes(const unsigned int mesh) const;

      /** As membrane_vertex_nodes() for solid mesh @p mesh. */
      std::vector<unsigned int>
      solid_vertex_nodes(const unsigned int mesh) const;

      /** As membrane_vertex_nodes() for plane solid mesh @p mesh (vertex
       * indices of its Triangulation<2,3>, those of the plane mesh given
       * to add_plane_solid()). */
      std::vector<unsigned int>
      plane_solid_vertex_nodes(const unsigned int mesh) const;

      /** Set the external force on @p node to @p F [N] (replacing the
       * previous one; not scaled by the load factor). */
      void
      set_external_force(const unsigned int          node,
                         const dealii::Tensor<1, 3> &F);

      /** External force on @p node [N]. */
      dealii::Tensor<1, 3>
      external_force(const unsigned int node) const;

      /** Set all external nodal forces to zero. */
      void
      clear_external_forces();
      /** @} */

      /** Write one VTU file per mesh (and a .pvd record over @p times). */
      void
      write_vtu(const dealii::Vector<double> &u,
                const std::string            &directory,
                const unsigned int            step,
                const double                  time);

      /** The records (time, file suffix) of the .pvd files of write_vtu(),
       * for a checkpoint: a resumed run's .pvd files list the outputs
       * before the checkpoint too. */
      std::vector<std::pair<double, std::string>> &
      vtu_records()
      {
        return pvd_records;
      }

      dealii::types::global_dof_index
      n_dofs() const;

      const dealii::AffineConstraints<double> &
      get_constraints() const;

      const dealii::SparsityPattern &
      get_sparsity_pattern() const;

      std::vector<std::unique_ptr<LineMesh>>       line_meshes;
      std::vector<std::unique_ptr<MembraneMesh>>   membrane_meshes;
      std::vector<std::unique_ptr<SolidMesh>>      solid_meshes;
      std::vector<std::unique_ptr<PlaneSolidMesh>> plane_solid_meshes;

      /** Call @p f on every solid mesh, three-dimensional then plane. */
      template <typename Function>
      void
      for_each_solid_mesh(const Function &f) const
      {
        for (const auto &mesh : solid_meshes)
          f(*mesh);
        for (const auto &mesh : plane_solid_meshes)
          f(*mesh);
      }

    private:
      dealii::FESystem<1, 3> line_fe{dealii::FE_Q<1, 3>(1), 3};
      dealii::FESystem<2, 3> membrane_fe{dealii::FE_Q<2, 3>(1), 3};

      /** Sets StructurePart::can_rotate and its axis (parts()); @p
       * part_index maps a global DoF to its part. */
      void
      find_rotation_mechanisms(
        std::vector<StructurePart> &parts,
        const std::function<unsigned int(dealii::types::global_dof_index)>
          &part_index) const;

      struct Node
      {
        dealii::Point<3>                                            X;
        std::array<dealii::types::global_dof_index, 3>              dofs;
        std::vector<std::array<dealii::types::global_dof_index, 3>> slaves;
      };
      std::vector<Node> nodes;
      /** Node of every global DoF (invalid for the DoFs of solids that
       * are not at a vertex). */
      std::vector<unsigned int> dof_to_node;
      /** Direction (0, 1, 2) of every global DoF. */
      std::vector<unsigned char> dof_component;
      /** Tractions of the solids at load factor 1, per DoF [N]. */
      dealii::Vector<double>          traction_forces;
      dealii::types::global_dof_index total_dofs = 0;

      std::vector<std::pair<dealii::types::global_dof_index, double>>
                                                                 prescribed;
      std::vector<std::pair<unsigned int, dealii::Tensor<1, 3>>> point_loads;

      dealii::AffineConstraints<double> ties;
      dealii::AffineConstraints<double> constraints;
      dealii::SparsityPattern           sparsity;
      /** Unconstrained f_int - f_ext of the last assembly (reactions). */
      dealii::Vector<double> raw_residual;
      dealii::Vector<double> mass;
      double                 last_strain_energy = 0.;

      std::vector<std::pair<double, std::string>> pvd_records;
    };
  } // namespace Structure
} // namespace Talus

#endif
