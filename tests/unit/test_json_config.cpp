
TEST(JsonConfig, APatchCaseMeshIsANameFromTheListNeverAPath) {
  const std::filesystem::path meshes = std::filesystem::path(NEEDLEKIT_SOURCE_DIR) / "data" / "meshes";
  const std::map<std::string, std::filesystem::path> offered{
      {"skull_yahoojapan_10k.obj", meshes / "skull_yahoojapan_10k.obj"}};
  const auto case_with = [](std::string_view mesh) {
    return fmt::format(R"({{"surface": {{"mesh": "{}", "unit": "15.8 mm", "center_vertex": 3627}},
        "patch": {{"kind": "rigid", "size": "10 mm", "needles_per_row": 10, "spring_constant": "1 N/mm"}},
        "needle": {{"shape": "cylinder", "tip_diameter": "70 um", "length": "400 um", "material": "su-8"}}}})",
                       mesh);
  };
  const io::PatchCase c = io::parse_patch_case_json(case_with("skull_yahoojapan_10k.obj"), "patch.json", offered);
  EXPECT_EQ(c.mesh, meshes / "skull_yahoojapan_10k.obj");
  EXPECT_DOUBLE_EQ(c.mesh_unit, 0.0158);
  for (std::string_view bad : {"../../etc/passwd", "/etc/passwd", "skull_yahoojapan_10k.obj/../README.md", "README.md",
                               ""}) {
    EXPECT_THAT(message_of([&] { io::parse_patch_case_json(case_with(bad), "patch.json", offered); }),
                HasSubstr(fmt::format("patch.json:1: key 'surface.mesh': '{}' is not one of the meshes offered, "
                                      "expected one of: skull_yahoojapan_10k.obj",
                                      bad)))
        << bad;
  }
  // A name whose file is not that name (a caller's mistake) is refused too.
  const std::map<std::string, std::filesystem::path> wrong{{"a.obj", meshes / "skull_yahoojapan_10k.obj"}};
  EXPECT_THAT(message_of([&] { io::parse_patch_case_json(case_with("a.obj"), "patch.json", wrong); }),
              HasSubstr("is not one of the meshes offered"));
}
