// The Structure and its solvers as the coupling will use them
// (doc/architecture.md, "The structure module"):
//  - several meshes (two cables and a post) tied at a common vertex: node
//    count, tied DoFs equal their master after a solve
//  - external nodal forces set from outside (Structure::external_forces):
//    the reactions balance them (global equilibrium to round-off)
//  - DynamicSolver::solve_step() is repeatable: solving again from the same
//    committed state, also after a solve with other external forces (a
//    coupling iteration), gives the same displacement; commit_step()
//    advances
//  - the load potential and the lumped mass (total mass = sum rho A L)
//  - the coupling interface on a net (membrane mesh with a tied edge
//    cable): membrane_vertex_nodes(), node_current_position(),
//    set_external_force() each time step of a DynamicSolver loop; the
//    forces read back sum to what was set, the positions are X + u, and a
//    static solve with the same forces is balanced by the reactions
//  - a continuum solid (an obstacle) tied to a cable: solid_vertex_nodes(),
//    the cable's end shares the node of the block's top-centre vertex,
//    supports on a boundary id, external forces on the top face balanced
//    by the reactions; with FE_Q(2) the lumped mass (row sums, also on
//    the DoFs that are not at a vertex) sums to rho V

#include <talus/structure/dynamic_solver.h>
#include <talus/structure/static_solver.h>
#include <talus/structure/structure.h>

#include <deal.II/grid/grid_generator.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>

using namespace dealii;
using namespace Talus::Structure;

namespace
{
  std::ofstream out("output");

  void
  line(Triangulation<1, 3> &tria, const Point<3> &a, const Point<3> &b, int n)
  {
    std::vector<Point<3>>    x;
    std::vector<CellData<1>> cells(n);
    for (int i = 0; i <= n; ++i)
      x.push_back(a + (b - a) * (double(i) / n));
    for (int i = 0; i < n; ++i)
      cells[i].vertices = {unsigned(i), unsigned(i + 1)};
    tria.create_triangulation(x, cells, SubCellData());
  }

  void
  build(Structure &s)
  {
    auto cable            = std::make_shared<Cable>();
    cable->youngs_modulus = 1e11;
    cable->area           = 1e-4;
    cable->prestress      = 1e8;
    cable->density        = 8000;
    auto post             = std::make_shared<Truss>();
    post->youngs_modulus  = 2e11;
    post->area            = 1e-3;
    post->density         = 8000;
    line(s.add_line_mesh("cable_a", cable).triangulation,
         Point<3>(0, 0, 0),
         Point<3>(1, 0, 0),
         2);
    line(s.add_line_mesh("cable_b", cable).triangulation,
         Point<3>(1, 0, 0),
         Point<3>(2, 0, 0),
         1);
    line(s.add_line_mesh("post", post).triangulation,
         Point<3>(1, 0, 0),
         Point<3>(1, 0, -1),
         1);
    s.setup_dofs();
    for (const Point<3> p :
         {Point<3>(0, 0, 0), Point<3>(2, 0, 0), Point<3>(1, 0, -1)})
      for (unsigned int c = 0; c < 3; ++c)
        s.prescribe(s.find_node(p, 1e-12), c);
    s.setup_system();
  }
} // namespace


int
main()
{
  out << std::setprecision(10);
  Structure s;
  build(s);
  out << "nodes: " << s.n_nodes() << ", DoFs (with tied copies): " << s.n_dofs()
      << '\n';
  double mass = 0.;
  for (unsigned int i = 0; i < s.n_dofs(); ++i)
    mass += s.lumped_mass()[i];
  out << "lumped mass (x, y, z summed): " << mass / 3.
      << " kg (8000 (1e-4 * 2 + 1e-3 * 1) = 9.6)\n";

  // Static: external forces at the joint and at the middle of cable_a.
  StaticSolver solver(s);
  solver.setup();
  const unsigned int joint = s.find_node(Point<3>(1, 0, 0), 1e-12);
  const unsigned int mid   = s.find_node(Point<3>(0.5, 0, 0), 1e-12);
  s.external_forces[s.node_dof(joint, 2)] = 2000.;
  s.external_forces[s.node_dof(joint, 1)] = 300.;
  s.external_forces[s.node_dof(mid, 2)]   = -500.;
  const auto status                       = solver.solve(1.);
  out << "static solve: converged " << status.converged << '\n';
  Tensor<1, 3> sum;
  for (const unsigned int n : {s.find_node(Point<3>(0, 0, 0), 1e-12),
                               s.find_node(Point<3>(2, 0, 0), 1e-12),
                               s.find_node(Point<3>(1, 0, -1), 1e-12)})
    sum += s.reaction(n);
  const Tensor<1, 3> F({0., 300., 1500.});
  out << "sum of reactions + external forces: "
      << ((sum + F).norm() < 1e-9 * F.norm() ? "0 (to 1e-9)" : "NOT ZERO")
      << '\n';
  out << "post force: " << s.line_meshes[2]->force[0]
      << " N (tension, carries most of the 2 kN at the joint)\n";
  // Tied copies equal their master.
  double tie_error = 0.;
  for (const auto &mesh : s.line_meshes)
    for (const auto &cell : mesh->dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          const unsigned int n = s.find_node(cell->vertex(v), 1e-12);
          for (unsigned int c = 0; c < 3; ++c)
            tie_error =
              std::max(tie_error,
                       std::abs(
                         solver.displacement[mesh->offset +
                                             cell->vertex_dof_index(v, c)] -
                         solver.displacement[s.node_dof(n, c)]));
        }
  out << "largest difference of tied copies: " << tie_error << '\n';

  // Dynamics: repeatable solve_step with changing external forces.
  DynamicSolver dynamics(s, solver);
  dynamics.enabled = true;
  dynamics.initialize();
  const auto step = [&](const double Fz) {
    s.external_forces[s.node_dof(joint, 2)] = Fz;
    const auto st                           = dynamics.solve_step(1e-4);
    return std::make_pair(st.converged, solver.displacement);
  };
  const auto     first = step(4000.);
  const auto     other = step(-3000.);
  const auto     again = step(4000.);
  Vector<double> d     = first.second;
  d -= again.second;
  Vector<double> d2 = first.second;
  d2 -= other.second;
  out << "solve_step converged: " << first.first << other.first << again.first
      << '\n'
      << "same forces again gives the same step: "
      << (d.linfty_norm() == 0. ? "identical" : "DIFFERENT") << '\n'
      << "other forces give another step: "
      << (d2.linfty_norm() > 0. ? "yes" : "NO") << '\n';
  dynamics.commit_step();
  out << "after commit_step: kinetic energy > 0: "
      << (dynamics.kinetic_energy() > 0. ? "yes" : "no") << '\n';

  // The coupling interface on a net: a 1 m x 1 m membrane (4 x 4 cells,
  // pre-stressed 1000 N/m) with a cable along its edge y = 0 tied to it;
  // boundary fixed.
  {
    Structure net;
    auto      cable       = std::make_shared<Cable>();
    cable->youngs_modulus = 1e11;
    cable->area           = 1e-4;
    cable->prestress      = 1e8;
    cable->density        = 8000;
    line(net.add_line_mesh("edge_cable", cable).triangulation,
         Point<3>(0, 0, 0),
         Point<3>(1, 0, 0),
         4);
    auto membrane                = std::make_shared<Membrane>();
    membrane->material.thickness = 1e-3;
    membrane->material.set_isotropic(1e9, 0.3);
    membrane->material.prestress = Tensor<1, 3>({1e6, 1e6, 0.});
    membrane->density            = 1000.;
    {
      Triangulation<2> flat;
      GridGenerator::subdivided_hyper_cube(flat, 4);
      GridGenerator::flatten_triangulation(
        flat, net.add_membrane("net", membrane).triangulation);
    }
    net.setup_dofs();
    std::vector<unsigned int> boundary;
    for (unsigned int n = 0; n < net.n_nodes(); ++n)
      {
        const Point<3> &X = net.node_position(n);
        if (X[0] < 1e-12 || X[0] > 1 - 1e-12 || X[1] < 1e-12 ||
            X[1] > 1 - 1e-12)
          {
            boundary.push_back(n);
            for (unsigned int c = 0; c < 3; ++c)
              net.prescribe(n, c);
          }
      }
    net.setup_system();

    const auto   vertex_nodes = net.membrane_vertex_nodes(0);
    const auto  &tria         = net.membrane_meshes[0]->triangulation;
    double       map_error    = 0.;
    unsigned int n_valid      = 0;
    for (unsigned int v = 0; v < vertex_nodes.size(); ++v)
      if (vertex_nodes[v] != numbers::invalid_unsigned_int)
        {
          ++n_valid;
          map_error = std::max(map_error,
                               tria.get_vertices()[v].distance(
                                 net.node_position(vertex_nodes[v])));
        }
    const auto   cable_nodes = net.line_vertex_nodes(0);
    unsigned int shared      = 0;
    for (const unsigned int n : cable_nodes)
      shared += std::count(vertex_nodes.begin(), vertex_nodes.end(), n);
    out << "net: " << n_valid << " vertices -> nodes (of " << net.n_nodes()
        << " nodes), largest |X_vertex - X_node| = " << map_error
        << "; edge cable nodes that are net nodes: " << shared << " of "
        << cable_nodes.size() << '\n';

    StaticSolver net_solver(net);
    net_solver.setup();
    DynamicSolver coupled(net, net_solver);
    coupled.enabled = true;
    coupled.initialize();
    // The coupling loop: forces from outside (here a pressure-like load
    // growing in time, 1/16 m^2 per interior node), one step, positions
    // read back.
    double       position_error = 0., force_error = 0.;
    unsigned int converged = 0;
    const double dt        = 1e-3;
    for (unsigned int k = 1; k <= 5; ++k)
      {
        net.clear_external_forces();
        Tensor<1, 3> total;
        for (const unsigned int n : vertex_nodes)
          if (std::find(boundary.begin(), boundary.end(), n) == boundary.end())
            {
              const Tensor<1, 3> F({0., 0., -20. * k / 16.});
              net.set_external_force(n, F);
              total += F;
            }
        Tensor<1, 3> read_back;
        for (unsigned int n = 0; n < net.n_nodes(); ++n)
          read_back += net.external_force(n);
        force_error = std::max(force_error, (read_back - total).norm());
        converged += coupled.solve_step(dt).converged;
        coupled.commit_step();
        for (const unsigned int n : vertex_nodes)
          position_error =
            std::max(position_error,
                     (net.node_current_position(net_solver.displacement, n) -
                      (net.node_position(n) +
                       net.node_displacement(net_solver.displacement, n)))
                       .norm());
      }
    const unsigned int centre = net.find_node(Point<3>(0.5, 0.5, 0), 1e-12);
    out << "coupling loop: " << converged << " of 5 steps converged; forces "
        << "read back - set: " << force_error
        << " N; |position - (X + u)|: " << position_error
        << " m; centre moved down: "
        << (net.node_current_position(net_solver.displacement, centre)[2] < 0. ?
              "yes" :
              "no")
        << '\n';
    // Static equilibrium with the last forces: the reactions balance them.
    const auto   st = net_solver.solve(0.);
    Tensor<1, 3> R, F;
    for (const unsigned int n : boundary)
      R += net.reaction(n);
    for (unsigned int n = 0; n < net.n_nodes(); ++n)
      F += net.external_force(n);
    out << "static solve with the coupling forces: converged " << st.converged
        << ", |sum of reactions + forces| / |forces| "
        << ((R + F).norm() < 1e-9 * F.norm() ? "< 1e-9" : "NOT SMALL") << '\n';
  }
  // A solid obstacle tied to a cable.
  for (const unsigned int degree : {1u, 2u})
    {
      Structure obstacle;
      auto      cable       = std::make_shared<Cable>();
      cable->youngs_modulus = 1e11;
      cable->area           = 1e-4;
      cable->prestress      = 1e8;
      cable->density        = 8000;
      line(obstacle.add_line_mesh("cable", cable).triangulation,
           Point<3>(0.5, 0.5, 2),
           Point<3>(0.5, 0.5, 1),
           2);
      auto solid            = std::make_shared<ContinuumSolid<3>>();
      solid->youngs_modulus = 1e9;
      solid->poissons_ratio = 0.25;
      solid->density        = 2000.;
      solid->degree         = degree;
      auto &block           = obstacle.add_solid("block", solid);
      GridGenerator::subdivided_hyper_rectangle(block.triangulation,
                                                {2, 2, 2},
                                                Point<3>(0, 0, 0),
                                                Point<3>(1, 1, 1),
                                                true);
      obstacle.setup_dofs();
      const unsigned int fixed = obstacle.prescribe_solid_boundary(0, 4);
      const unsigned int anchor =
        obstacle.find_node(Point<3>(0.5, 0.5, 2), 1e-12);
      for (unsigned int c = 0; c < 3; ++c)
        obstacle.prescribe(anchor, c);
      obstacle.setup_system();
      const auto   vertex_nodes = obstacle.solid_vertex_nodes(0);
      const auto   cable_nodes  = obstacle.line_vertex_nodes(0);
      unsigned int shared       = 0;
      for (const unsigned int n : vertex_nodes)
        shared += std::count(cable_nodes.begin(), cable_nodes.end(), n);
      double mass = 0.;
      for (unsigned int i = 0; i < obstacle.n_dofs(); ++i)
        mass += obstacle.lumped_mass()[i];
      out << "solid FE_Q(" << degree
          << ") tied to a cable: " << obstacle.n_nodes() << " nodes, "
          << obstacle.n_dofs() << " DoFs, bottom face: " << fixed
          << " DoFs fixed; vertices of the block that are cable nodes: "
          << shared << "; lumped mass (x, y, z summed) / 3 = " << mass / 3.
          << " kg (rho V + 8000 * 1e-4 * 1 = 2000.8)\n";
      if (degree == 2)
        continue;
      // Horizontal forces on the top face, balanced by the supports.
      StaticSolver obstacle_solver(obstacle);
      obstacle_solver.setup();
      Tensor<1, 3> F;
      for (unsigned int v = 0; v < vertex_nodes.size(); ++v)
        if (std::abs(obstacle.node_position(vertex_nodes[v])[2] - 1.) < 1e-12)
          {
            const Tensor<1, 3> f({1000., 200., 0.});
            obstacle.set_external_force(vertex_nodes[v], f);
            F += f;
          }
      const auto   st = obstacle_solver.solve(1.);
      Tensor<1, 3> R;
      for (unsigned int n = 0; n < obstacle.n_nodes(); ++n)
        R += obstacle.reaction(n);
      out << "  static solve with " << F << " N on the top face: converged "
          << st.converged << ", |sum of reactions + forces| / |forces| "
          << ((R + F).norm() < 1e-9 * F.norm() ? "< 1e-9" : "NOT SMALL")
          << ", top centre moved along x: "
          << (obstacle.node_displacement(
                obstacle_solver.displacement,
                obstacle.find_node(Point<3>(0.5, 0.5, 1), 1e-12))[0] > 0. ?
                "yes" :
                "no")
          << '\n';
    }
  return 0;
}
