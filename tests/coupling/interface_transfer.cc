// InterfaceTransfer: the consistent displacement and conservative force
// transfer between a structure's interface mesh and the boundary
// particles, against closed forms, on a bent string (Triangulation<1,2>,
// the 2D barrier) and a warped membrane (Triangulation<2,3>, the net):
//  - the points are the Gauss points of the mesh refined twice (as
//    BoundaryParticles::set_surface() makes them: the particles lie in
//    children of the structure's cells);
//  - FE interpolation reproduces a linear displacement field exactly on
//    straight / flat cells: u_p = A X_p + b (error ~ round-off);
//  - for random nodal displacements U and random point forces f_p the
//    summed force and the interface work agree on both sides to round-off:
//    sum_i F_i = sum_p f_p and U . F = sum_p u_p . f_p;
//  - a point off the mesh is rejected with a message.

#include <talus/coupling/interface_transfer.h>

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <random>
#include <string>
#include <vector>

#include "check.h"

using namespace dealii;

namespace
{
  /** The Gauss points of @p tria refined twice (a copy). */
  template <int dim, int spacedim>
  std::vector<Point<spacedim>>
  particles_of(const Triangulation<dim, spacedim> &tria)
  {
    Triangulation<dim, spacedim> fine;
    fine.copy_triangulation(tria);
    fine.refine_global(2);
    const MappingQ1<dim, spacedim> mapping;
    const FE_Q<dim, spacedim>      fe(1);
    const QGauss<dim>              quadrature(2);
    FEValues<dim, spacedim>        fe_values(mapping,
                                      fe,
                                      quadrature,
                                      update_quadrature_points);
    std::vector<Point<spacedim>>   x;
    for (const auto &cell : fine.active_cell_iterators())
      {
        fe_values.reinit(cell);
        for (const auto &q : fe_values.get_quadrature_points())
          x.push_back(q);
      }
    return x;
  }

  template <int dim, int spacedim>
  void
  check_transfer(const Triangulation<dim, spacedim> &tria,
                 const std::string                  &name,
                 std::ostream                       &out)
  {
    DoFHandler<dim, spacedim>     dof_handler(tria);
    const FESystem<dim, spacedim> fe(FE_Q<dim, spacedim>(1), spacedim);
    dof_handler.distribute_dofs(fe);
    const auto points = particles_of(tria);

    Talus::Coupling::InterfaceTransfer<dim, spacedim> transfer;
    transfer.reinit(dof_handler, points);
    out << name << ": " << tria.n_active_cells() << " cells, "
        << transfer.n_points() << " points\n";

    // a linear field u = A x + b at the nodes
    Tensor<2, spacedim> A;
    Tensor<1, spacedim> b;
    for (unsigned int i = 0; i < spacedim; ++i)
      {
        b[i] = 0.1 * (i + 1);
        for (unsigned int j = 0; j < spacedim; ++j)
          A[i][j] = 0.01 * (1 + i + 2 * j);
      }
    Vector<double>                       U(dof_handler.n_dofs());
    const MappingQ1<dim, spacedim>       mapping;
    std::vector<types::global_dof_index> dofs(fe.dofs_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < fe.dofs_per_cell; ++i)
          {
            const auto            ci = fe.system_to_component_index(i);
            const Point<spacedim> x  = cell->vertex(ci.second);
            U(dofs[i])               = (A * x + b)[ci.first];
          }
      }
    const auto u     = transfer.interpolate(U);
    double     error = 0.;
    for (unsigned int p = 0; p < points.size(); ++p)
      error = std::max(error, (u[p] - (A * points[p] + b)).norm());
    CouplingTests::check(out,
                         error < 1e-14,
                         "linear field reproduced (error < 1e-14 m)");

    // random U and f: conservation of force and work
    std::mt19937                           rng(42);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    for (auto &v : U)
      v = uniform(rng);
    std::vector<Tensor<1, spacedim>> f(points.size());
    for (auto &fp : f)
      for (unsigned int d = 0; d < spacedim; ++d)
        fp[d] = 1e3 * uniform(rng);
    Vector<double> F(dof_handler.n_dofs());
    transfer.distribute(f, F);
    const auto          up = transfer.interpolate(U);
    Tensor<1, spacedim> sum_f, sum_F;
    double              work_points = 0., scale = 0.;
    for (unsigned int p = 0; p < points.size(); ++p)
      {
        sum_f += f[p];
        work_points += up[p] * f[p];
        scale += up[p].norm() * f[p].norm();
      }
    std::vector<unsigned int> component(dof_handler.n_dofs());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < fe.dofs_per_cell; ++i)
          component[dofs[i]] = fe.system_to_component_index(i).first;
      }
    for (unsigned int i = 0; i < dof_handler.n_dofs(); ++i)
      sum_F[component[i]] += F(i);
    double f_scale = 0.;
    for (const auto &fp : f)
      f_scale += fp.norm();
    CouplingTests::check(out,
                         (sum_F - sum_f).norm() <= 1e-13 * f_scale,
                         "summed force equal on both sides (relative 1e-13)");
    CouplingTests::check(out,
                         std::abs(U * F - work_points) <= 1e-13 * scale,
                         "interface work equal on both sides (relative "
                         "1e-13)");

    // a point off the mesh
    std::vector<Point<spacedim>> off = {points[0]};
    off[0][spacedim - 1] += 0.5;
    bool rejected = false;
    try
      {
        Talus::Coupling::InterfaceTransfer<dim, spacedim> bad;
        bad.reinit(dof_handler, off);
      }
    catch (const std::exception &e)
      {
        rejected = std::string(e.what()).find("does not lie on the interface "
                                              "mesh") != std::string::npos;
      }
    CouplingTests::check(out, rejected, "a point off the mesh is rejected");
  }
} // namespace


int
main()
{
  std::ofstream out("output");
  {
    // a bent string of four cells in the plane (the 2D barrier)
    Triangulation<1, 2>         string;
    const std::vector<Point<2>> v = {Point<2>(0, 0),
                                     Point<2>(0.3, 0.1),
                                     Point<2>(0.7, 0.05),
                                     Point<2>(1.0, 0.4),
                                     Point<2>(1.2, 0.9)};
    std::vector<CellData<1>>    cells(4);
    for (unsigned int c = 0; c < 4; ++c)
      cells[c].vertices = {c, c + 1};
    string.create_triangulation(v, cells, SubCellData());
    check_transfer(string, "string Triangulation<1,2>", out);
  }
  {
    // a net of 4 x 3 flat quadrilaterals, rotated out of the coordinate
    // planes (the membrane)
    Triangulation<2, 3> net;
    Triangulation<2, 2> plane;
    GridGenerator::subdivided_hyper_rectangle(plane,
                                              {4, 3},
                                              Point<2>(0, 0),
                                              Point<2>(5, 3.5));
    GridGenerator::flatten_triangulation(plane, net);
    GridTools::transform(
      [](const Point<3> &x) {
        // rotation by 30 degrees about the x axis, then a shift
        const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
        return Point<3>(x[0] + 1., c * x[1] - s * x[2], s * x[1] + c * x[2]);
      },
      net);
    check_transfer(net, "membrane Triangulation<2,3>", out);
  }
}
