#pragma once
// glTF 2.0 binary (.glb) of the structure model, through TinyGLTF (Debian libtinygltf-dev).
// glTF is y-up: the model keeps site coordinates (z up, metres) in its meshes and one root node
// turns them (-90 degrees about x), so that a viewer stands the structure upright and the site
// coordinates are what a CAD import that undoes the turn sees. Node tree:
//   eggshell <name>            extras: units, up axis, centreline source, deviation scale
//     surface                  the design surface (translucent)
//     P<k>                     extras: patch
//       P<k>-U, P<k>-V         one node per family
//         P<k>-U<i>            one lamella: a solid ribbon w x t coloured by deviation (COLOR_0);
//                              extras: id, patch, family, index, length_m, spatial_length_m,
//                              max_deviation_m, sheet
//       P<k>-bolts             every bolt of the patch (extras: ids)
//     supports                 S<nnn> nodes: the support blocks at their site positions
#include "export/model.hpp"

#include <string>

namespace egg::exporter {

// What goes into the file besides the lamellas.
struct GlbContents {
  bool surface = true;
  bool lamellas = true;
  bool bolts = true;
  bool supports = true;
};

// The .glb bytes. Throws InvalidInput (model.validate()) or Error when TinyGLTF cannot serialise.
std::string glbBytes(const StructureModel& model, const GlbContents& contents = {});

// The supports alone (supports.glb): the same tree with only the supports node's children.
std::string supportsGlbBytes(const StructureModel& model);

}  // namespace egg::exporter
