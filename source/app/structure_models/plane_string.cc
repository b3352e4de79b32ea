// Structure model: a pre-tensioned straight string of a 2D problem, the
// barrier of the coupled 2D verification cases (set problem = structure or
// coupled).

#include <talus/app/structure_models/factory.h>
#include <talus/app/structure_models/model.h>
#include <talus/structure/plane_string.h>
#include <talus/structure/structure.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace Talus
{
  namespace StructureModels
  {
    namespace
    {
      using namespace dealii;

      /**
       * A straight string of 'span' along x, centred at 'origin' (x, y of
       * the 2D problem), 'elements per member' line elements (cable or
       * truss) with the pre-stress 'prestress', both ends fixed: a
       * PlaneString (Triangulation<1,2> solved in the plane z = 0). Its
       * mesh is called "string" (the coupling's 'structure mesh'). In 2D
       * every force and E A is per metre of out-of-plane width.
       *
       * Reference under self weight w = rho A g alone (small sag, Hooke's
       * law): the parabola with H = w L^2 / (8 f) and H = N_0 + E A
       * (8/3) (f/L)^2, N_0 = sigma_0 A (printed, not checked: the
       * element's Green-Lagrange law and the parabola are approximations
       * of the same order).
       */
      class PlaneStringModel : public Model
      {
      public:
        using Model::Model;

        std::string
        description() const override
        {
          return "pre-tensioned straight string of a 2D problem "
                 "(Triangulation<1,2>)";
        }

        bool
        supports_dynamics() const override
        {
          return true;
        }

        void
        build(Structure &s, const unsigned int level) override
        {
          const unsigned int       n = p.elements << level;
          std::vector<Point<2>>    x(n + 1);
          std::vector<CellData<1>> cells(n);
          for (unsigned int i = 0; i <= n; ++i)
            x[i] = Point<2>(p.origin[0] - 0.5 * p.span + p.span * i / n,
                            p.origin[1]);
          for (unsigned int i = 0; i < n; ++i)
            cells[i].vertices = {i, i + 1};
          string.triangulation.create_triangulation(x, cells, SubCellData());
          s.gravity = p.gravity;
          string.add_to(s, "string", line_element());
          s.setup_dofs();
          string.setup(s);
          string.fix(s, 0);
          string.fix(s, n);
          mid = n / 2;
        }

        std::vector<Result>
        results(const Structure &s, const Vector<double> &u) override
        {
          const double w  = p.density * p.A * p.gravity.norm();
          const double EA = p.E * p.A, N0 = p.prestress * p.A, L = p.span;
          const double f = bisect(
            [&](const double f) {
              return w * L * L / (8. * f) - N0 -
                     EA * 8. / 3. * (f / L) * (f / L);
            },
            1e-12 * L,
            L);
          const double sag =
            p.origin[1] - string.current_position(s, u, mid)[1];
          return {
            {"mid-span sag [m]", sag, f, false},
            {"support force [N]", string.reaction(s, 0).norm(), 0., false}};
        }

      private:
        Talus::Structure::PlaneString string;
        unsigned int                  mid = 0;
      };
    } // namespace


    std::unique_ptr<Model>
    create_plane_string(const Parameters &p)
    {
      return std::make_unique<PlaneStringModel>(p);
    }
  } // namespace StructureModels
} // namespace Talus
