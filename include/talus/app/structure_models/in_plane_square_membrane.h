#ifndef talus_app_structure_models_in_plane_square_membrane_h
#define talus_app_structure_models_in_plane_square_membrane_h

#include <talus/app/structure_models/model.h>

namespace Talus
{
  namespace StructureModels
  {

    /**
     * A flat square membrane (side a, centred at the origin, in the x-y
     * plane, 'refinements' + level times refined) loaded in its plane:
     * u_z = 0 at every node (a flat membrane has no stiffness normal to
     * itself before it is stressed); no pre-stress step.
     */
    class InPlaneSquareMembrane : public Model
    {
    public:
      using Model::Model;

      bool
      prestress_step() const override
      {
        return false;
      }

    protected:
      /** The mesh, setup_dofs() and u_z = 0 everywhere. */
      void
      build_square(Structure &s, const unsigned int level) const
      {
        make_flat_mesh(s.add_membrane("membrane", membrane()).triangulation,
                       false,
                       p.side,
                       p.refinements + level);
        s.setup_dofs();
        for (unsigned int n = 0; n < s.n_nodes(); ++n)
          s.prescribe(n, 2);
      }
    };
  } // namespace StructureModels
} // namespace Talus

#endif
