// §6.4 of `needlekit reproduce`: rigid vs flexible patch on the neck (Figs 6.21-6.24), the energy sweep (Fig 6.25),
// the colour maps of Fig 6.26 and the skull patches of Fig 6.27.
#include "reproduce_sections.hpp"

namespace needlekit::cli::reproduce {

std::vector<std::filesystem::path> section_6_4_mesh_files(const RunContext& context) {
  return {context.meshes / "vh_male_head_neck_loop2.obj",
          context.meshes / (context.quick ? "skull_yahoojapan_10k.obj" : "skull_yahoojapan_100k.obj")};
}

SectionReport section_6_4(const RunContext& /*context*/, const SectionProgress& progress) {
  SectionReport report("6.4", "§6.4 Rigid and flexible microneedle patches on skin and skull");
  report.unavailable("not available in this build: the patch-fitting capability (issue 5) is not part of it");
  progress(1, "done");
  return report;
}

}  // namespace needlekit::cli::reproduce
