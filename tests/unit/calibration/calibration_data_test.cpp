// Tests of the calibration CSV reader and the checks of column-compression and direct-shear
// tables: what is accepted, and that every rejection names the file, the line and the column.
#include <gtest/gtest.h>

#include <sstream>

#include "blockdem/calibration/calibration_data.hpp"
#include "calibration_test_support.hpp"

namespace blockdem {
namespace {

using test::calibration_error;

CalibrationTable parse(const std::string& text, const std::vector<std::string>& columns) {
  std::istringstream in(text);
  return parse_calibration_csv(in, "lab.csv", columns);
}

const std::vector<std::string> kColumn = {"stress_Pa", "displacement_m"};
const std::vector<std::string> kShear = {"normal_stress_Pa", "shear_displacement_m",
                                         "shear_stress_Pa"};

TEST(CalibrationCsv, SkipsCommentsAndBlankLinesAndMapsColumnsByName) {
  // Columns in another order than requested, a '#' header, blank lines, CRLF, a '+' sign.
  const CalibrationTable t = parse(
      "# SYNTHETIC DATA, test\r\n\n  # second comment\ndisplacement_m , stress_Pa\r\n"
      "0,0\n1.5e-6,+2e4\n\n# between rows\n3e-6,4e4\n",
      kColumn);
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.comments,
            (std::vector<std::string>{"SYNTHETIC DATA, test", "second comment", "between rows"}));
  EXPECT_EQ(t.rows[1], (std::vector<double>{2e4, 1.5e-6}));
  EXPECT_EQ(t.rows[2], (std::vector<double>{4e4, 3e-6}));
  EXPECT_EQ(t.lines, (std::vector<int>{5, 6, 9}));
  EXPECT_EQ(t.where(2), "lab.csv:9");
}

TEST(CalibrationCsv, RejectsMissingUnexpectedAndRepeatedColumns) {
  const std::string missing = calibration_error([] { parse("stress_Pa\n1\n", kColumn); });
  EXPECT_NE(missing.find("lab.csv:1"), std::string::npos) << missing;
  EXPECT_NE(missing.find("missing column 'displacement_m'"), std::string::npos) << missing;

  const std::string unexpected =
      calibration_error([] { parse("# c\nstress_Pa,displacement_m,time_s\n", kColumn); });
  EXPECT_NE(unexpected.find("lab.csv:2"), std::string::npos) << unexpected;
  EXPECT_NE(unexpected.find("unexpected column 'time_s'"), std::string::npos) << unexpected;

  const std::string twice =
      calibration_error([] { parse("stress_Pa,stress_Pa,displacement_m\n", kColumn); });
  EXPECT_NE(twice.find("'stress_Pa' appears twice"), std::string::npos) << twice;

  EXPECT_NE(calibration_error([] { parse("# only comments\n", kColumn); }).find("no header"),
            std::string::npos);
  EXPECT_NE(
      calibration_error([] { parse("stress_Pa,displacement_m\n", kColumn); }).find("no data rows"),
      std::string::npos);
}

TEST(CalibrationCsv, RejectsNaNInfinityTextEmptyFieldsAndRaggedRows) {
  const std::string header = "stress_Pa,displacement_m\n1,1\n";
  const auto error_for = [&](const std::string& row) {
    return calibration_error([&] { parse(header + row + "\n", kColumn); });
  };
  const std::string nan = error_for("2,nan");
  EXPECT_NE(nan.find("lab.csv:3"), std::string::npos) << nan;
  EXPECT_NE(nan.find("'displacement_m' is nan"), std::string::npos) << nan;
  EXPECT_NE(error_for("inf,1").find("'stress_Pa' is inf"), std::string::npos);
  EXPECT_NE(error_for("2,1.0mm").find("'1.0mm' is not a number"), std::string::npos);
  EXPECT_NE(error_for("2,").find("'displacement_m' is empty"), std::string::npos);
  EXPECT_NE(error_for("2").find("expected 2 values"), std::string::npos);
  EXPECT_NE(error_for("2,1,3").find("found 3"), std::string::npos);
}

TEST(CalibrationCsv, ReportsAnUnreadableFile) {
  const std::string e = calibration_error(
      [] { read_calibration_csv(test::scratch_directory() / "does_not_exist.csv", kColumn); });
  EXPECT_NE(e.find("does_not_exist.csv: cannot open"), std::string::npos) << e;
}

TEST(ColumnCompressionData, AcceptsAnIncreasingLoadingBranch) {
  const ColumnCompressionData d = column_compression_data(parse(
      "stress_Pa,displacement_m\n0,0\n1e5,1e-5\n2e5,1.6e-5\n3e5,2e-5\n4e5,2.3e-5\n", kColumn));
  EXPECT_EQ(d.stress.size(), 5u);
  EXPECT_EQ(d.displacement[2], 1.6e-5);
  EXPECT_EQ(d.lines.front(), 2);
}

TEST(ColumnCompressionData, RejectsNegativeNonMonotonicAndTooFewRows) {
  const std::string header = "stress_Pa,displacement_m\n";
  const auto error_for = [&](const std::string& rows) {
    return calibration_error([&] { column_compression_data(parse(header + rows, kColumn)); });
  };
  const std::string negative = error_for("0,0\n-1e5,1e-5\n");
  EXPECT_NE(negative.find("lab.csv:3: stress_Pa = -1e+05 is negative"), std::string::npos)
      << negative;
  const std::string unloading = error_for("0,0\n2e5,1e-5\n1e5,0.8e-5\n3e5,2e-5\n4e5,3e-5\n");
  EXPECT_NE(unloading.find("lab.csv:4: stress_Pa = 1e+05 is not greater"), std::string::npos)
      << unloading;
  EXPECT_NE(error_for("0,0\n1e5,-1e-5\n").find("displacement_m = -1e-05 is negative"),
            std::string::npos);
  const std::string few = error_for("0,0\n1e5,1e-5\n2e5,2e-5\n");
  EXPECT_NE(few.find("lab.csv: 3 data rows"), std::string::npos) << few;
}

std::string shear_rows(double sigma, int rows) {
  std::string out;
  for (int i = 0; i < rows; ++i) {
    out += std::to_string(sigma) + "," + std::to_string(1e-6 * i) + "," +
           std::to_string(0.1 * sigma * i) + "\n";
  }
  return out;
}

TEST(DirectShearData, GroupsContiguousRowsByNormalStress) {
  const std::string header = "normal_stress_Pa,shear_displacement_m,shear_stress_Pa\n";
  const DirectShearData d = direct_shear_data(
      parse(header + shear_rows(1e4, 5) + shear_rows(2e4, 6) + shear_rows(4e4, 7), kShear));
  ASSERT_EQ(d.curves.size(), 3u);
  EXPECT_EQ(d.curves[1].normal_stress, 2e4);
  EXPECT_EQ(d.curves[1].displacement.size(), 6u);
  EXPECT_EQ(d.curves[2].lines.front(), 13);
}

TEST(DirectShearData, RejectsBadRowsSplitCurvesAndTooLittleData) {
  const std::string header = "normal_stress_Pa,shear_displacement_m,shear_stress_Pa\n";
  const auto error_for = [&](const std::string& rows) {
    return calibration_error([&] { direct_shear_data(parse(header + rows, kShear)); });
  };
  EXPECT_NE(error_for("0,0,0\n").find("lab.csv:2: normal_stress_Pa = 0 must be positive"),
            std::string::npos);
  EXPECT_NE(error_for("1e4,0,-5\n").find("shear_stress_Pa = -5 is negative"), std::string::npos);
  EXPECT_NE(error_for("1e4,-1e-6,0\n").find("shear_displacement_m = -1e-06 is negative"),
            std::string::npos);
  const std::string backwards = error_for("1e4,0,0\n1e4,2e-6,10\n1e4,1e-6,20\n");
  EXPECT_NE(backwards.find("lab.csv:4: shear_displacement_m = 1e-06 is not greater"),
            std::string::npos)
      << backwards;
  const std::string split = error_for(shear_rows(1e4, 5) + shear_rows(2e4, 5) + shear_rows(1e4, 5));
  EXPECT_NE(split.find("lab.csv:12: normal_stress_Pa = 10000 was already given"), std::string::npos)
      << split;
  const std::string short_curve =
      error_for(shear_rows(1e4, 5) + shear_rows(2e4, 3) + shear_rows(3e4, 5));
  EXPECT_NE(short_curve.find("lab.csv:7: the curve at normal stress 20000 Pa has 3 rows"),
            std::string::npos)
      << short_curve;
  const std::string two = error_for(shear_rows(1e4, 5) + shear_rows(2e4, 5));
  EXPECT_NE(two.find("2 normal stress(es)"), std::string::npos) << two;
}

}  // namespace
}  // namespace blockdem
