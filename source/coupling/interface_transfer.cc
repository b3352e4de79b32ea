#include <talus/coupling/interface_transfer.h>

#include <deal.II/base/quadrature.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/grid_tools_cache.h>

#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <sstream>
#include <stdexcept>

namespace Talus
{
  namespace Coupling
  {
    template <int dim, int spacedim>
    void
    InterfaceTransfer<dim, spacedim>::reinit(
      const dealii::DoFHandler<dim, spacedim>    &dof_handler,
      const std::vector<dealii::Point<spacedim>> &points,
      const double                                tolerance)
    {
      const auto &tria = dof_handler.get_triangulation();
      const dealii::MappingQ1<dim, spacedim>        mapping;
      const auto                                   &fe = dof_handler.get_fe();
      const dealii::GridTools::Cache<dim, spacedim> cache(tria, mapping);
      point_cells.resize(points.size());
      reference_points.resize(points.size());
      point_dofs.assign(points.size(), {});
      point_shapes.assign(points.size(), {});
      for (unsigned int p = 0; p < points.size(); ++p)
        {
          // the cell the point lies in (once: transfers never search)
          std::pair<
            typename dealii::Triangulation<dim, spacedim>::active_cell_iterator,
            dealii::Point<dim>>
            found;
          try
            {
              found =
                dealii::GridTools::find_active_cell_around_point(cache,
                                                                 points[p]);
            }
          catch (...)
            {
              found.first = tria.end();
            }
          const auto cell  = found.first;
          bool       close = cell != tria.end() &&
                       cell.state() == dealii::IteratorState::valid &&
                       dealii::GeometryInfo<dim>::distance_to_unit_cell(
                         found.second) <= tolerance;
          if (close)
            {
              // codimension one: the point must lie on the cell, not only
              // project onto it
              const dealii::Point<spacedim> x =
                mapping.transform_unit_to_real_cell(cell, found.second);
              close = x.distance(points[p]) <= tolerance * cell->diameter();
            }
          if (!close)
            {
              std::ostringstream msg;
              msg << "InterfaceTransfer: the point (" << points[p]
                  << ") does not lie on the interface mesh ("
                  << tria.n_active_cells()
                  << " cells): the boundary particles must be points of the "
                     "structure's interface mesh in its reference "
                     "configuration";
              throw std::runtime_error(msg.str());
            }
          point_cells[p]      = cell->active_cell_index();
          reference_points[p] = found.second;
          const typename dealii::DoFHandler<dim, spacedim>::active_cell_iterator
            dof_cell(&tria, cell->level(), cell->index(), &dof_handler);
          dealii::FEValues<dim, spacedim> fe_values(
            mapping,
            fe,
            dealii::Quadrature<dim>(
              std::vector<dealii::Point<dim>>{found.second}),
            dealii::update_values);
          fe_values.reinit(dof_cell);
          point_dofs[p].resize(fe.dofs_per_cell);
          dof_cell->get_dof_indices(point_dofs[p]);
          for (unsigned int i = 0; i < fe.dofs_per_cell; ++i)
            {
              const unsigned int c = fe.system_to_component_index(i).first;
              point_shapes[p].emplace_back(
                c, fe_values.shape_value_component(i, 0, c));
            }
        }
    }


    template <int dim, int spacedim>
    std::vector<dealii::Tensor<1, spacedim>>
    InterfaceTransfer<dim, spacedim>::interpolate(
      const dealii::Vector<double> &U) const
    {
      std::vector<dealii::Tensor<1, spacedim>> u(point_dofs.size());
      for (unsigned int p = 0; p < point_dofs.size(); ++p)
        for (unsigned int i = 0; i < point_dofs[p].size(); ++i)
          u[p][point_shapes[p][i].first] +=
            point_shapes[p][i].second * U(point_dofs[p][i]);
      return u;
    }


    template <int dim, int spacedim>
    void
    InterfaceTransfer<dim, spacedim>::distribute(
      const std::vector<dealii::Tensor<1, spacedim>> &f,
      dealii::Vector<double>                         &F) const
    {
      AssertDimension(f.size(), point_dofs.size());
      for (unsigned int p = 0; p < point_dofs.size(); ++p)
        for (unsigned int i = 0; i < point_dofs[p].size(); ++i)
          F(point_dofs[p][i]) +=
            point_shapes[p][i].second * f[p][point_shapes[p][i].first];
    }


    template class InterfaceTransfer<1, 2>;
    template class InterfaceTransfer<2, 3>;
  } // namespace Coupling
} // namespace Talus
