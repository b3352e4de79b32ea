// Helpers shared by the structure verification models.

#include <talus/app/structure_models/model.h>
#include <talus/base/input.h>

#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

namespace Talus
{
  namespace StructureModels
  {
    using namespace dealii;


    double
    bisect(const std::function<double(double)> &f, double a, double b)
    {
      double fa = f(a);
      for (unsigned int i = 0; i < 200; ++i)
        {
          const double m  = 0.5 * (a + b);
          const double fm = f(m);
          if ((fm <= 0.) == (fa <= 0.))
            {
              a  = m;
              fa = fm;
            }
          else
            b = m;
        }
      return 0.5 * (a + b);
    }


    Tensor<1, 3>
    get_vector(ParameterHandler  &prm,
               const std::string &subsection,
               const std::string &entry)
    {
      const auto v = Utilities::string_to_double(
        Utilities::split_string_list(prm.get(entry)));
      if (v.size() != 3)
        InputFile::reject(subsection,
                          entry,
                          prm.get(entry),
                          "it must have three components x, y, z");
      return Tensor<1, 3>({v[0], v[1], v[2]});
    }


    template <int spacedim>
    void
    make_line(Triangulation<1, spacedim> &tria,
              const Point<spacedim>      &a,
              const Point<spacedim>      &b,
              const unsigned int          n)
    {
      std::vector<Point<spacedim>> vertices(n + 1);
      std::vector<CellData<1>>     cells(n);
      for (unsigned int i = 0; i <= n; ++i)
        vertices[i] = a + (b - a) * (static_cast<double>(i) / n);
      for (unsigned int i = 0; i < n; ++i)
        cells[i].vertices = {i, i + 1};
      tria.create_triangulation(vertices, cells, SubCellData());
    }


    template void
    make_line(Triangulation<1, 2> &,
              const Point<2> &,
              const Point<2> &,
              const unsigned int);
    template void
    make_line(Triangulation<1, 3> &,
              const Point<3> &,
              const Point<3> &,
              const unsigned int);


    void
    make_polyline(Triangulation<1, 3> &tria, const std::vector<Point<3>> &x)
    {
      std::vector<CellData<1>> cells(x.size() - 1);
      for (unsigned int i = 0; i + 1 < x.size(); ++i)
        cells[i].vertices = {i, i + 1};
      tria.create_triangulation(x, cells, SubCellData());
    }


    void
    make_flat_mesh(Triangulation<2, 3> &tria,
                   const bool           disk,
                   const double         size,
                   const unsigned int   refinements)
    {
      Triangulation<2> flat;
      if (disk)
        GridGenerator::hyper_ball(flat, Point<2>(), size);
      else
        GridGenerator::hyper_cube(flat, -0.5 * size, 0.5 * size);
      flat.refine_global(refinements);
      GridGenerator::flatten_triangulation(flat, tria);
    }


    std::vector<std::pair<std::string, double>>
    structure_columns(const Structure &s)
    {
      std::vector<std::pair<std::string, double>> c = {
        {"strain_energy", s.strain_energy()}};
      for (const auto &m : s.line_meshes)
        {
          double f = 0.;
          for (const double x : m->force)
            f = std::max(f, std::abs(x));
          c.emplace_back(m->name + "_max_force", f);
          if (m->element && m->element->name() == "brake")
            {
              double stroke = 0., D = 0.;
              for (const auto &st : m->state)
                {
                  stroke = std::max(stroke, st.plastic);
                  D += st.accumulated;
                }
              c.emplace_back(m->name + "_max_stroke", stroke);
              c.emplace_back(m->name + "_dissipated_energy", D);
            }
        }
      return c;
    }
  } // namespace StructureModels
} // namespace Talus
