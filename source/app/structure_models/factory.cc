// The structure model a file asks for (subsection Structure, model).

#include <talus/app/structure_models/factory.h>

namespace Talus
{
  namespace StructureModels
  {
    std::unique_ptr<Model>
    create_model(const Parameters &p)
    {
      if (p.model == "vibrating string")
        return create_vibrating_string(p);
      if (p.model == "sheared membrane")
        return create_sheared_membrane(p);
      if (p.model == "stretched membrane")
        return create_stretched_membrane(p);
      if (p.model == "plastic bar")
        return create_plastic_bar(p);
      if (p.model == "capstan")
        return create_capstan(p);
      if (p.model == "barrier")
        return create_barrier(p);
      if (p.model == "solid")
        return create_solid_model(p);
      if (p.model == "cantilever")
        return create_cantilever(p);
      if (p.model == "hanging block")
        return create_hanging_block(p);
      if (p.model == "axial bar")
        return create_axial_bar(p);
      if (p.model == "von Mises truss")
        return create_von_mises_truss(p);
      if (p.model == "catenary" || p.model == "plane catenary")
        return create_catenary(p);
      if (p.model == "circular membrane")
        return create_circular_membrane(p);
      if (p.model == "square membrane")
        return create_square_membrane(p);
      if (p.model == "sliding ring")
        return create_sliding_ring(p);
      if (p.model == "plane string")
        return create_plane_string(p);
      if (p.model == "plane barrier")
        return create_plane_barrier(p);
      if (p.model == "brake")
        return create_brake_test(p);
      if (p.model == "midspan cable")
        return create_midspan_cable(p);
      return create_line_from_file(p);
    }
  } // namespace StructureModels
} // namespace Talus
