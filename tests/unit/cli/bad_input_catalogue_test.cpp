// A catalogue of bad input across the subcommands. Each case must exit with code 2, print a
// message that starts with "blockdem:" and names the file (where there is one), the key and the
// reason, and write nothing. Scenario cases are mutations of one good two-block scenario.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/input_error.hpp"

namespace blockdem {
namespace {

namespace fs = std::filesystem;

const std::string kGood = R"(title = "two blocks"
[settings]
damping = 0.7
[[materials]]
name = "rock"
density = 2600
[[joint_laws]]
name = "j"
normal = { law = "linear", stiffness = 1e10 }
shear = { law = "linear", stiffness = 1e9, friction_deg = 30 }
[[blocks]]
name = "base"
material = "rock"
size = [1, 1, 0.2]
position = [0, 0, -0.1]
motion = "fixed"
[[blocks]]
name = "top"
material = "rock"
size = [0.2, 0.2, 0.2]
position = [0, 0, 0.1]
[[stages]]
name = "settle"
gravity = [0, 0, -9.81]
max_steps = 2000
)";

struct ScenarioCase {
  const char* name;
  std::string from;  ///< text of kGood to replace ("" appends `to` to the file)
  std::string to;
  std::string key;     ///< expected in the message
  std::string reason;  ///< expected in the message
};

fs::path scratch(const std::string& name) {
  return test::fresh_case_dir("bad_input", name);
}

// Stands in a case's text for an array of a million and one block names (6 MB), which mutate()
// writes out when the case runs: every test process registers every case, and the array made
// and copied at registration cost each of them about 0.1 s before its own test began.
const std::string kMillionNames = "<1000001 block names>";

std::string mutate(const ScenarioCase& c) {
  std::string s = kGood;
  if (c.from.empty()) {
    s += c.to + "\n";
  } else {
    const auto at = s.find(c.from);
    EXPECT_NE(at, std::string::npos) << c.name << ": '" << c.from << "' is not in the scenario";
    if (at != std::string::npos) s.replace(at, c.from.size(), c.to);
  }
  if (const auto at = s.find(kMillionNames); at != std::string::npos) {
    std::string names;
    names.reserve(6 * 1000001);
    for (int i = 0; i < 1000001; ++i) names += "\"top\",";
    s.replace(at, kMillionNames.size(), names);
  }
  return s;
}

class BadScenario : public ::testing::TestWithParam<ScenarioCase> {};

TEST(BadScenario, TheGoodScenarioRuns) {
  const fs::path dir = scratch("good");
  std::ofstream(dir / "case.toml") << kGood;
  const auto r = test::run_cli("run '" + (dir / "case.toml").string() + "' --out '" +
                               (dir / "out").string() + "' --quiet --no-figures");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "summary.json"));
}

TEST_P(BadScenario, ExitsTwoNamingFileKeyAndReasonAndWritesNothing) {
  const ScenarioCase& c = GetParam();
  const fs::path dir = scratch(c.name);
  const fs::path file = dir / "case.toml";
  std::ofstream(file) << mutate(c);
  const fs::path out = dir / "out";
  const auto r = test::run_cli("run '" + file.string() + "' --out '" + out.string() +
                               "' --quiet --no-figures");
  test::expect_input_error(r, out, {file.string(), c.key, c.reason});
}

const std::string kTop = "name = \"top\"\nmaterial = \"rock\"\nsize = [0.2, 0.2, 0.2]\n";
// A bolt down through the top block into the base; each case adds its start and length.
const std::string kBolt =
    "[[bolts]]\nname = \"B1\"\ndirection = [0, 0, -1]\naxial_stiffness = 1e7\n"
    "install_stage = \"settle\"\n";
// A bolt pattern on an excavation the scenario does not have; each case adds its spacing.
const std::string kPattern =
    "[[bolt_patterns]]\nexcavation = \"tunnel\"\nlength = 0.3\naxial_stiffness = 1e7\n"
    "install_stage = \"settle\"\n";

INSTANTIATE_TEST_SUITE_P(
    Catalogue, BadScenario,
    ::testing::Values(
        ScenarioCase{"syntax", "title = \"two blocks\"", "title = \"two blocks", "", "TOML syntax"},
        ScenarioCase{"unknown_top_key", "", "colour = \"red\"", "colour", "unknown"},
        ScenarioCase{"unknown_setting", "damping = 0.7", "damping = 0.7\nspeed = 2",
                     "settings.speed", "unknown"},
        ScenarioCase{"damping_above_one", "damping = 0.7", "damping = 1.5", "settings.damping",
                     "[0, 1)"},
        ScenarioCase{"time_step_negative", "damping = 0.7", "damping = 0.7\ntime_step = -1",
                     "settings.time_step", "positive"},
        ScenarioCase{"time_step_word", "damping = 0.7", "damping = 0.7\ntime_step = \"fast\"",
                     "settings.time_step", "auto"},
        ScenarioCase{"safety_factor_above_one", "damping = 0.7", "damping = 0.7\nsafety_factor = 2",
                     "settings.safety_factor", "at most 1"},
        ScenarioCase{"contact_mode_unknown", "damping = 0.7",
                     "damping = 0.7\ncontact_mode = \"magic\"", "settings.contact_mode", "magic"},
        ScenarioCase{"face_angle_too_wide", "damping = 0.7", "damping = 0.7\nface_angle_deg = 60",
                     "settings.face_angle_deg", "45"},
        ScenarioCase{"rounding_zero", "damping = 0.7", "damping = 0.7\nrounding_distance = 0",
                     "settings.rounding_distance", "positive"},
        ScenarioCase{"rounding_beyond_block", "damping = 0.7",
                     "damping = 0.7\nrounding_distance = 0.5", "settings.rounding_distance",
                     "half-thickness"},
        ScenarioCase{"max_speed_negative", "damping = 0.7", "damping = 0.7\nmax_speed = -1",
                     "settings.max_speed", "positive"},
        ScenarioCase{"damping_string", "damping = 0.7", "damping = \"high\"", "settings.damping",
                     "number"},
        ScenarioCase{"material_twice", "density = 2600",
                     "density = 2600\n[[materials]]\nname = \"rock\"\ndensity = 2000", "materials",
                     "twice"},
        ScenarioCase{"material_density_zero", "density = 2600", "density = 0", "density",
                     "positive"},
        ScenarioCase{"material_unknown", "name = \"top\"\nmaterial = \"rock\"",
                     "name = \"top\"\nmaterial = \"granite\"", "material", "granite"},
        ScenarioCase{"material_and_density", "name = \"top\"\nmaterial = \"rock\"",
                     "name = \"top\"\nmaterial = \"rock\"\ndensity = 2000", "density", "not both"},
        ScenarioCase{"block_without_name", "name = \"top\"\n", "", "name", "required"},
        ScenarioCase{"block_twice", "name = \"top\"", "name = \"base\"", "name", "twice"},
        ScenarioCase{"box_side_negative", "size = [0.2, 0.2, 0.2]", "size = [0.2, -0.2, 0.2]",
                     "size", "positive"},
        ScenarioCase{"box_size_two_numbers", "size = [0.2, 0.2, 0.2]", "size = [0.2, 0.2]", "size",
                     "3"},
        ScenarioCase{"shape_unknown", kTop, kTop + "shape = \"sphere\"\n", "shape", "sphere"},
        ScenarioCase{"planes_open", kTop,
                     "name = \"top\"\nmaterial = \"rock\"\nshape = \"planes\"\n"
                     "planes = [[0, 0, 1, 0.1], [0, 0, -1, 0.1], [1, 0, 0, 0.1]]\n",
                     "planes", ""},
        ScenarioCase{"plane_zero_normal", kTop,
                     "name = \"top\"\nmaterial = \"rock\"\nshape = \"planes\"\n"
                     "planes = [[0, 0, 0, 0.1], [0, 0, -1, 0.1], [1, 0, 0, 0.1], "
                     "[-1, 0, 0, 0.1], [0, 1, 0, 0.1], [0, -1, 0, 0.1]]\n",
                     "planes", "zero vector"},
        ScenarioCase{"vertices_repeated", kTop,
                     "name = \"top\"\nmaterial = \"rock\"\nshape = \"vertices\"\n"
                     "vertices = [[0, 0, 0.01], [0.2, 0, 0.01], [0, 0.2, 0.01], [0, 0, 0.2], "
                     "[0.2, 0, 0.01]]\n",
                     "vertices", "repeats vertex 2"},
        ScenarioCase{"vertices_flat", kTop,
                     "name = \"top\"\nmaterial = \"rock\"\nshape = \"vertices\"\n"
                     "vertices = [[0, 0, 0.01], [0.2, 0, 0.01], [0, 0.2, 0.01], [0.2, 0.2, "
                     "0.01]]\n",
                     "vertices", ""},
        ScenarioCase{"position_huge", "position = [0, 0, 0.1]", "position = [1e300, 0, 0.1]",
                     "position", "1e12"},
        ScenarioCase{"rotation_axis_zero", "position = [0, 0, 0.1]",
                     "position = [0, 0, 0.1]\nrotation_deg = 10\nrotation_axis = [0, 0, 0]",
                     "rotation_axis", "non-zero"},
        ScenarioCase{"motion_unknown", "position = [0, 0, 0.1]",
                     "position = [0, 0, 0.1]\nmotion = \"flying\"", "motion", "flying"},
        ScenarioCase{"fixed_with_velocity", "motion = \"fixed\"",
                     "motion = \"fixed\"\nvelocity = [1, 0, 0]", "velocity", "fixed"},
        ScenarioCase{"servo_without_table", "position = [0, 0, 0.1]",
                     "position = [0, 0, 0.1]\nmotion = \"servo\"", "servo", "required"},
        ScenarioCase{"servo_axis_huge", "position = [0, 0, 0.1]",
                     "position = [0, 0, 0.1]\nmotion = \"servo\"\n"
                     "servo = { axis = [1e308, 1e308, 0], target_force = 10 }",
                     "axis", "finite"},
        ScenarioCase{"servo_table_on_free_block", "position = [0, 0, 0.1]",
                     "position = [0, 0, 0.1]\nservo = { axis = [1, 0, 0] }", "servo",
                     "only a block"},
        ScenarioCase{"blocked_dof_unknown", "position = [0, 0, 0.1]",
                     "position = [0, 0, 0.1]\nblocked_dofs = [\"w\"]", "blocked_dofs", "\"w\""},
        ScenarioCase{"law_kind_unknown", "law = \"linear\", stiffness = 1e10",
                     "law = \"cubic\", stiffness = 1e10", "normal", "cubic"},
        ScenarioCase{"law_stiffness_negative", "law = \"linear\", stiffness = 1e10",
                     "law = \"linear\", stiffness = -1e10", "normal", "stiffness"},
        ScenarioCase{"law_friction_95", "friction_deg = 30", "friction_deg = 95", "shear",
                     "friction"},
        ScenarioCase{"law_parameter_unknown", "friction_deg = 30",
                     "friction_deg = 30, stickiness = 2", "shear", "stickiness"},
        ScenarioCase{"law_without_shear",
                     "shear = { law = \"linear\", stiffness = 1e9, "
                     "friction_deg = 30 }",
                     "", "shear", "required"},
        ScenarioCase{"law_twice", "[[blocks]]\nname = \"base\"",
                     "[[joint_laws]]\nname = \"j\"\nnormal = { law = \"linear\", stiffness = 1e10 "
                     "}\nshear = { law = \"linear\", stiffness = 1e9, friction_deg = 30 "
                     "}\n[[blocks]]\nname = \"base\"",
                     "joint_laws", "twice"},
        ScenarioCase{"rule_unknown_group", "",
                     "[[joints]]\ngroups = [\"default\", \"soil\"]\nlaw = \"j\"", "joints", "soil"},
        ScenarioCase{"rule_unknown_law", "",
                     "[[joints]]\ngroups = [\"default\", \"default\"]\nlaw = \"bedding\"", "joints",
                     "bedding"},
        ScenarioCase{"rule_one_group", "", "[[joints]]\ngroups = [\"default\"]\nlaw = \"j\"",
                     "joints", "two block groups"},
        ScenarioCase{"two_laws_no_rule", "[[blocks]]\nname = \"base\"",
                     "[[joint_laws]]\nname = \"k\"\nnormal = { law = \"linear\", stiffness = 1e10 "
                     "}\nshear = { law = \"linear\", stiffness = 1e9, friction_deg = 30 "
                     "}\n[[blocks]]\nname = \"base\"",
                     "joints", "several joint laws"},
        ScenarioCase{"no_stages",
                     "[[stages]]\nname = \"settle\"\ngravity = [0, 0, -9.81]\nmax_steps = 2000\n",
                     "", "stages", "at least one"},
        ScenarioCase{"stage_kind_unknown", "max_steps = 2000", "max_steps = 2000\nkind = \"wait\"",
                     "kind", "wait"},
        ScenarioCase{"stage_damping", "max_steps = 2000", "max_steps = 2000\ndamping = 1.2",
                     "damping", "[0, 1)"},
        ScenarioCase{"stage_max_steps_zero", "max_steps = 2000", "max_steps = 0", "max_steps",
                     "between 1 and 1e12"},
        ScenarioCase{"stage_max_steps_huge", "max_steps = 2000", "max_steps = 9000000000000000000",
                     "max_steps", "between 1 and 1e12"},
        ScenarioCase{"stage_min_above_max", "max_steps = 2000",
                     "max_steps = 2000\nmin_steps = 3000", "min_steps", "max_steps"},
        ScenarioCase{"stage_steps_above_max", "max_steps = 2000",
                     "max_steps = 2000\nkind = \"steps\"\nsteps = 5000", "steps", "max_steps"},
        ScenarioCase{"stage_steps_missing", "max_steps = 2000",
                     "max_steps = 2000\nkind = \"steps\"", "steps", "steps > 0"},
        ScenarioCase{"factor_search_unknown", "max_steps = 2000",
                     "max_steps = 2000\nkind = \"strength_reduction\"\nfactor_search = \"newton\"",
                     "factor_search", "newton"},
        ScenarioCase{"factor_search_outside_a_search", "max_steps = 2000",
                     "max_steps = 2000\nfactor_search = \"bisect\"", "factor_search",
                     "strength_reduction"},
        ScenarioCase{"stage_ramp_without_gravity", "gravity = [0, 0, -9.81]", "ramp_steps = 10",
                     "ramp_steps", "gravity"},
        ScenarioCase{"stage_servo_unknown_block", "max_steps = 2000",
                     "max_steps = 2000\nservos = [{ block = \"ghost\", target_force = 1 }]",
                     "servos", "ghost"},
        ScenarioCase{"stage_hold_unknown_block", "max_steps = 2000",
                     "max_steps = 2000\nhold = [\"ghost\"]", "hold", "ghost"},
        ScenarioCase{"blocks_deep_overlap", "position = [0, 0, 0.1]", "position = [0, 0, 0.0]",
                     "blocks", "overlap"},
        ScenarioCase{"time_step_absurd", "density = 2600", "density = 1e-12", "settings.time_step",
                     "units"},
        ScenarioCase{"history_block_unknown", "", "[output]\nhistory_blocks = [\"ghost\"]",
                     "output.history_blocks", "ghost"},
        ScenarioCase{"history_interval_zero", "", "[output]\nhistory_interval = 0",
                     "output.history_interval", "positive"},
        ScenarioCase{"history_max_rows_one", "", "[output]\nhistory_max_rows = 1",
                     "output.history_max_rows", "at least 2"},
        ScenarioCase{"vtk_interval_negative", "", "[output]\nvtk_interval = -5",
                     "output.vtk_interval", "positive"},
        ScenarioCase{"bolt_outside_every_block", "", kBolt + "start = [0, 0, 0.5]\nlength = 0.3",
                     "bolts[1].start", "outside every block"},
        ScenarioCase{"bolt_crossing_no_joint", "", kBolt + "start = [0, 0, 0.2]\nlength = 0.1",
                     "bolts[1].start", "crosses no joint"},
        ScenarioCase{"bolt_beyond_the_rock", "", kBolt + "start = [0, 0, 0.2]\nlength = 0.5",
                     "bolts[1].start", "far end"},
        ScenarioCase{"bolt_length_zero", "", kBolt + "start = [0, 0, 0.2]\nlength = 0",
                     "bolts[1].length", "positive"},
        ScenarioCase{"bolt_stiffness_negative", "",
                     kBolt + "start = [0, 0, 0.2]\nlength = 0.3\nshear_stiffness = -1e8",
                     "bolts[1].shear_stiffness", "positive"},
        ScenarioCase{"bolt_shear_rupture_without_dowel", "",
                     kBolt + "start = [0, 0, 0.2]\nlength = 0.3\nshear_rupture_displacement = 0.01",
                     "bolts[1].shear_rupture_displacement", "needs a dowel"},
        ScenarioCase{"bolt_shear_rupture_negative", "",
                     kBolt + "start = [0, 0, 0.2]\nlength = 0.3\nshear_stiffness = 1e8\n"
                             "shear_rupture_displacement = -0.01",
                     "bolts[1].shear_rupture_displacement", "positive"},
        ScenarioCase{"bolt_stage_unknown", "",
                     "[[bolts]]\nname = \"B1\"\ndirection = [0, 0, -1]\naxial_stiffness = 1e7\n"
                     "start = [0, 0, 0.2]\nlength = 0.3\ninstall_stage = \"support\"",
                     "bolts[1].install_stage", "no stage named \"support\""},
        ScenarioCase{"bolt_unknown_key", "",
                     kBolt + "start = [0, 0, 0.2]\nlength = 0.3\ndiameter = 0.025",
                     "bolts[1].diameter", "unknown"},
        ScenarioCase{"bolt_pretension_grouted", "",
                     kBolt + "start = [0, 0, 0.2]\nlength = 0.3\nbond_stiffness = 1e8\n"
                             "pretension = 1e3",
                     "bolts[1].pretension", "point-anchored"},
        ScenarioCase{"bolt_pattern_spacing_zero", "", kPattern + "spacing = [0, 1.5]",
                     "bolt_patterns[1].spacing", "positive"},
        ScenarioCase{"bolt_pattern_unknown_excavation", "", kPattern + "spacing = [1.5, 1.5]",
                     "bolt_patterns[1].excavation", "no excavation named \"tunnel\""},
        ScenarioCase{"huge_array", "gravity = [0, 0, -9.81]",
                     "gravity = [0, 0, -9.81]\nhold = [" + kMillionNames + "]", "hold", "limit"},
        // Ground water and earthquakes (docs/water-and-earthquakes.md).
        ScenarioCase{"water_density_zero", "max_steps = 2000",
                     "max_steps = 2000\nwater_table = { point = [0, 0, 1], normal = [0, 0, 1] }\n"
                     "water_density = 0",
                     "water_density", "positive"},
        ScenarioCase{"water_density_nan", "damping = 0.7",
                     "damping = 0.7\nwater_table = { point = [0, 0, 1], normal = [0, 0, 1] }\n"
                     "water_density = nan",
                     "settings.water_density", "finite"},
        ScenarioCase{"water_density_alone", "max_steps = 2000",
                     "max_steps = 2000\nwater_density = 1000", "water_density", "water_table"},
        ScenarioCase{"water_table_two_points", "max_steps = 2000",
                     "max_steps = 2000\nwater_table = { points = [[0, 0, 1], [1, 0, 1]] }",
                     "water_table.points", "at least 3 points"},
        ScenarioCase{"water_table_point_inf", "damping = 0.7",
                     "damping = 0.7\nwater_table = { point = [0, 0, inf], normal = [0, 0, 1] }",
                     "settings.water_table", "finite"},
        ScenarioCase{"water_table_vertical", "max_steps = 2000",
                     "max_steps = 2000\nwater_table = { point = [0, 0, 1], normal = [1, 0, 0] }",
                     "water_table", "vertical"},
        ScenarioCase{"water_table_unknown_key", "max_steps = 2000",
                     "max_steps = 2000\nwater_table = { point = [0, 0, 1], normal = [0, 0, 1], "
                     "level = 3 }",
                     "water_table.level", "unknown"},
        ScenarioCase{"water_table_none_in_settings", "damping = 0.7",
                     "damping = 0.7\nwater_table = \"none\"", "settings.water_table", "point"},
        ScenarioCase{"seismic_kh_inf", "max_steps = 2000", "max_steps = 2000\nseismic_kh = inf",
                     "seismic_kh", "finite"},
        ScenarioCase{"seismic_kv_nan", "max_steps = 2000", "max_steps = 2000\nseismic_kv = nan",
                     "seismic_kv", "finite"},
        ScenarioCase{"seismic_unknown_key", "max_steps = 2000",
                     "max_steps = 2000\nseismic_kx = 0.1", "seismic_kx", "unknown"},
        ScenarioCase{"seismic_collapse_with_gravity", "max_steps = 2000",
                     "max_steps = 2000\nseismic_kh = 0.1\nfind_collapse = true", "find_collapse",
                     "either gravity"}),
    [](const ::testing::TestParamInfo<ScenarioCase>& p) { return std::string(p.param.name); });

// The voussoir builder's own checks.
struct VoussoirCase {
  const char* name;
  std::string table;  ///< the [voussoir] table's extra lines
  std::string key;
  std::string reason;
};

class BadVoussoir : public ::testing::TestWithParam<VoussoirCase> {};

TEST_P(BadVoussoir, ExitsTwoNamingFileKeyAndReasonAndWritesNothing) {
  const VoussoirCase& c = GetParam();
  const fs::path dir = scratch(std::string("voussoir_") + c.name);
  const fs::path file = dir / "beam.toml";
  std::ofstream(file) << "[voussoir]\n"
                      << c.table
                      << "\nnormal = { law = \"linear\", stiffness = 1e10 }\n"
                         "shear = { law = \"linear\", stiffness = 1e9, friction_deg = 40 }\n";
  const fs::path out = dir / "out";
  const auto r = test::run_cli("run '" + file.string() + "' --out '" + out.string() +
                               "' --quiet --no-figures");
  test::expect_input_error(r, out, {file.string(), c.key, c.reason});
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, BadVoussoir,
    ::testing::Values(
        VoussoirCase{"no_blocks", "blocks = 0", "voussoir.blocks", "at least one"},
        VoussoirCase{"negative_length", "block_length = -0.046", "voussoir.block_length",
                     "positive"},
        VoussoirCase{"g_below_one", "g_max = 0.5", "voussoir.g_max", "at least 1"},
        VoussoirCase{"g_levels_and_g_max", "g_levels = [2, 5]\ng_max = 10", "voussoir.g_max",
                     "not both"},
        VoussoirCase{"beam_unknown", "beam = \"quarter\"", "voussoir.beam", "quarter"},
        VoussoirCase{"steps_overflow", "max_steps_per_level = 9223372036854775807",
                     "voussoir.max_steps_per_level", "1e12"},
        VoussoirCase{"unreachable_preload", "preload_force = 1e9", "voussoir.preload_force",
                     "cannot be reached"},
        VoussoirCase{"servo_side", "servo_side = \"middle\"", "voussoir.servo_side", "middle"}),
    [](const ::testing::TestParamInfo<VoussoirCase>& p) { return std::string(p.param.name); });

// The other subcommands: their files and values.
struct CommandCase {
  const char* name;
  std::string arguments;  ///< OUT: a fresh output folder; DATA: a bad data file of this case
  std::string data;       ///< the bad data file's text, when the case needs one
  std::vector<std::string> fragments;
};

class BadCommand : public ::testing::TestWithParam<CommandCase> {};

TEST_P(BadCommand, ExitsTwoWithAMessageAndWritesNothing) {
  const CommandCase& c = GetParam();
  const fs::path dir = scratch(std::string("command_") + c.name);
  const fs::path out = dir / "out";
  const fs::path data = dir / "data.csv";
  if (!c.data.empty()) std::ofstream(data) << c.data;
  std::string args = c.arguments;
  for (const auto& [token, value] :
       {std::pair<std::string, fs::path>{"OUT", out}, {"DATA", data}}) {
    const auto at = args.find(token);
    if (at != std::string::npos) args.replace(at, token.size(), "'" + value.string() + "'");
  }
  test::expect_input_error(test::run_cli(args), out, c.fragments);
}

const std::string kCalibrate = "calibrate normal --modulus 5.6e9 --height 0.138 --joints 3 ";

INSTANTIATE_TEST_SUITE_P(
    Catalogue, BadCommand,
    ::testing::Values(
        CommandCase{"reproduce_unknown_study", "reproduce boon2099 --out OUT", "", {"boon2099"}},
        CommandCase{"reproduce_unknown_case", "reproduce boon2015 --case T9 --out OUT", "", {"T9"}},
        CommandCase{"reproduce_jobs_zero", "reproduce boon2015 --jobs 0 --out OUT", "", {"jobs"}},
        CommandCase{"reproduce_no_out", "reproduce boon2015", "", {"--out"}},
        CommandCase{"lab_no_path",
                    "lab compression --normal 'law=linear,stiffness=1e10' --out OUT",
                    "",
                    {"--max-closure"}},
        CommandCase{"lab_unknown_law",
                    "lab compression --normal 'law=cubic' --max-closure 1e-4 --out OUT",
                    "",
                    {"cubic"}},
        CommandCase{"lab_shear_negative_stress",
                    "lab shear --shear 'law=linear,stiffness=1e9,friction_deg=40' "
                    "--normal-stress -1 --max-shear-displacement 1e-3 --out OUT",
                    "",
                    {"normal"}},
        CommandCase{"lab_bad_mode",
                    "lab compression --normal 'law=linear,stiffness=1e10' --max-closure 1e-4 "
                    "--dem --mode sideways --out OUT",
                    "",
                    {"sideways"}},
        CommandCase{"calibrate_missing_file",
                    kCalibrate + "--data /no/such.csv --out OUT",
                    "",
                    {"/no/such.csv"}},
        CommandCase{"calibrate_no_rows",
                    kCalibrate + "--data DATA --out OUT",
                    "normal_stress_Pa,displacement_m\n",
                    {"data.csv"}},
        CommandCase{"calibrate_text_in_number",
                    kCalibrate + "--data DATA --out OUT",
                    "stress_Pa,displacement_m\n1e5,abc\n2e5,2e-5\n3e5,3e-5\n",
                    {"data.csv", "abc"}},
        CommandCase{"calibrate_wrong_columns",
                    kCalibrate + "--data DATA --out OUT",
                    "stress,disp\n1e5,1e-5\n2e5,2e-5\n3e5,3e-5\n",
                    {"data.csv"}},
        CommandCase{"calibrate_negative_modulus",
                    "calibrate normal --modulus -5.6e9 --height 0.138 --joints 3 --data DATA "
                    "--out OUT",
                    "normal_stress_Pa,displacement_m\n1e5,1e-5\n2e5,2e-5\n3e5,3e-5\n",
                    {"modulus"}},
        CommandCase{"analytic_negative_span",
                    "analytic voussoir --span -1 --depth 0.046 --density 1207 --gravity 9.81 "
                    "--modulus 4.6e8",
                    "",
                    {"span"}},
        CommandCase{"analytic_zero_density",
                    "analytic voussoir --span 0.276 --depth 0.046 --density 0 --gravity 9.81 "
                    "--modulus 4.6e8",
                    "",
                    {"density"}},
        CommandCase{"analytic_missing_modulus",
                    "analytic voussoir --span 0.276 --depth 0.046 --density 1207 --gravity 9.81",
                    "",
                    {"modulus"}}),
    [](const ::testing::TestParamInfo<CommandCase>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace blockdem
