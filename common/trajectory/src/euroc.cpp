// EuRoC ASL ground truth (Burri et al., IJRR 2016): state_groundtruth_estimate0/data.csv, 17 columns.
#include "checks.hpp"
#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam {

Trajectory read_euroc_groundtruth(const std::filesystem::path& file) {
  Trajectory trajectory;
  trajectory.source = file.string();
  // Only the first 8 columns are used, but the row width is still checked: a truncated row is a broken file.
  read_csv(file, 0, [&](const CsvRow& row) {
    if (row.cells.size() < 8) {
      throw InputError(where(file.string(), row.line,
                             "expected at least 8 columns (timestamp, p_RS_R xyz, q_RS wxyz), found " +
                                 std::to_string(row.cells.size())));
    }
    const std::int64_t stamp_ns = parse_int64(file, row, 0, "timestamp");
    const Eigen::Vector3d p_RS(parse_double(file, row, 1, "p_RS_R_x"), parse_double(file, row, 2, "p_RS_R_y"),
                               parse_double(file, row, 3, "p_RS_R_z"));
    const Eigen::Quaterniond q_RS(parse_double(file, row, 4, "q_RS_w"), parse_double(file, row, 5, "q_RS_x"),
                                  parse_double(file, row, 6, "q_RS_y"), parse_double(file, row, 7, "q_RS_z"));
    detail::check_unit_quaternion(file, row.line, q_RS);
    detail::append_increasing(file, row.line, trajectory, make_pose(stamp_ns, p_RS, q_RS));
  });
  detail::check_not_empty(file, trajectory);
  return trajectory;
}

}  // namespace twinslam
