// furnish(): furniture and clutter the drawing does not show (declared in world_fittings.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "floorgrid/simulation/drawing_raster.hpp"
#include "floorgrid/simulation/world_fittings.hpp"

namespace floorgrid::plan_world {

namespace {

constexpr double kWallGap = 0.03;         // metres between a piece and the wall behind it
constexpr double kSpacing = 0.1;          // metres between pieces
constexpr double kFullyLinedArea = 40.0;  // square metres: larger rooms are lined less
constexpr double kSnap = 12.0 * std::numbers::pi / 180.0;  // to the building's axes

struct Piece {
  const char* what;
  UniformRange length, depth;
};

// Pieces against walls: rooms hold office and home furniture, corridors clutter.
constexpr Piece kRoomPieces[] = {{"cabinet", {0.8, 2.0}, {0.4, 0.6}},
                                 {"desk", {1.2, 1.8}, {0.7, 0.8}},
                                 {"shelf", {0.9, 3.0}, {0.3, 0.45}},
                                 {"sofa", {1.6, 2.2}, {0.8, 0.95}}};
constexpr double kRoomOdds[] = {0.35, 0.3, 0.2, 0.15};
constexpr Piece kCorridorPieces[] = {{"bin", {0.3, 0.6}, {0.3, 0.5}},
                                     {"bench", {1.0, 1.8}, {0.4, 0.5}},
                                     {"cabinet", {0.8, 1.2}, {0.4, 0.5}}};
constexpr double kCorridorOdds[] = {0.5, 0.3, 0.2};

template <std::size_t N>
const Piece& pick(const Piece (&pieces)[N], const double (&odds)[N], Random& random) {
  double u = random.uniform();
  for (std::size_t i = 0; i < N; ++i) {
    if (u < odds[i])
      return pieces[i];
    u -= odds[i];
  }
  return pieces[N - 1];
}

// What furnishing consults and updates.
struct Furnisher {
  WorldCanvas& c;
  const PlanWorldOptions& o;
  Random& random;
  Eigen::Vector2d axis;  // the building's main direction
  cv::Mat keep_free;     // doorways and their approaches
  cv::Mat taken;         // placed pieces grown by kSpacing
  cv::Mat free;          // inside, and nothing solid there

  // Turns a direction onto the building's axes when it is near one.
  Eigen::Vector2d snapped(const Eigen::Vector2d& n) const {
    for (const Eigen::Vector2d& a :
         {axis, left_of(axis), Eigen::Vector2d(-axis), Eigen::Vector2d(-left_of(axis))}) {
      if (std::acos(std::clamp(n.dot(a), -1.0, 1.0)) < kSnap)
        return a;
    }
    return n;
  }

  // Places `outline` when it fits: inside region `region`, on nothing, clear of doorways and
  // other pieces.
  bool fits(const std::vector<Eigen::Vector2d>& outline, int region) const {
    const auto [pixels, solid] = outline_pixels(c.solid, c.geometry, outline);
    const auto [n1, inside] = outline_pixels(c.solids.inside, c.geometry, outline);
    const auto [n2, door] = outline_pixels(keep_free, c.geometry, outline);
    const auto [n3, near] = outline_pixels(taken, c.geometry, outline);
    if (pixels == 0 || solid > 0.02 * pixels || inside < 0.98 * n1 || door > 0 || near > 0)
      return false;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& p : outline)
      centre += p / double(outline.size());
    const cv::Point px = pixel_of(c.geometry, centre);
    return is_set(c.solids.inside, px) && c.rooms.labels.at<int>(px) == region;
  }

  void place(const char* what, std::vector<Eigen::Vector2d> outline, int region,
             const Eigen::Vector2d& centre, const Eigen::Vector2d& u, double length, double depth) {
    fill_outline(taken, c.geometry,
                 oriented_box(centre, u, length + 2 * kSpacing, depth + 2 * kSpacing));
    fill_outline(free, c.geometry, outline, 0);
    c.add({SurfaceKind::furniture, what, std::move(outline), region});
  }

  // A piece against the wall nearest `p` (a pixel next to a wall face); false when it does not
  // fit or would narrow the room below `passage`.
  bool against_wall(const cv::Mat& to_wall, const cv::Point& p, int region, const Piece& piece) {
    const GridGeometry& g = c.geometry;
    const int x = p.x, y = p.y;
    if (x < 2 || y < 2 || x + 2 >= to_wall.cols || y + 2 >= to_wall.rows)
      return false;
    Eigen::Vector2d n(to_wall.at<float>(y, x + 2) - to_wall.at<float>(y, x - 2),
                      to_wall.at<float>(y + 2, x) - to_wall.at<float>(y - 2, x));
    if (n.norm() < 1.0)
      return false;  // a corner or a thin gap: no single wall
    n = snapped(n.normalized());
    const Eigen::Vector2d u = left_of(n);
    const double length = random.uniform(piece.length.min, piece.length.max);
    const double depth = random.uniform(piece.depth.min, piece.depth.max);
    const Eigen::Vector2d face = g.cell_center(x, y) - n * (to_wall.at<float>(y, x) * g.resolution);
    const Eigen::Vector2d centre = face + n * (kWallGap + depth / 2);
    const auto outline = oriented_box(centre, u, length, depth);
    if (!fits(outline, region))
      return false;
    const Eigen::Vector2d front = centre + n * (depth / 2 + g.resolution);
    for (const double t : {-0.45, 0.0, 0.45}) {
      if (run_length(free, g, front + u * (t * length), n, o.passage) < o.passage)
        return false;
    }
    place(piece.what, outline, region, centre, u, length, depth);
    if (std::string(piece.what) == "desk" && random.bernoulli(0.7)) {
      const Eigen::Vector2d seat = centre + n * (depth / 2 + 0.35);
      const auto chair = oriented_box(seat, u, 0.46, 0.46);
      if (fits(chair, region))
        place("chair", chair, region, seat, u, 0.46, 0.46);
    }
    return true;
  }

  void line_walls(const cv::Mat& to_wall) {
    // Pixels next to a wall face, per region.
    std::vector<std::vector<cv::Point>> faces(c.rooms.regions.size());
    for (int y = 0; y < to_wall.rows; ++y) {
      const float* d = to_wall.ptr<float>(y);
      const int* label = c.rooms.labels.ptr<int>(y);
      for (int x = 0; x < to_wall.cols; ++x) {
        if (label[x] >= 0 && d[x] >= 1.0f && d[x] < 2.0f)
          faces[static_cast<std::size_t>(label[x])].emplace_back(x, y);
      }
    }
    for (std::size_t r = 0; r < faces.size(); ++r) {
      if (faces[r].empty())
        continue;
      const bool corridor = c.rooms.regions[r].kind == "corridor";
      // Large rooms (labs, open-plan offices) are lined less: as much furniture as a room of
      // kFullyLinedArea holds, spread along more wall.
      const double area = c.rooms.regions[r].area;
      const double density = (corridor ? o.corridor_furniture : o.wall_furniture) *
                             std::sqrt(std::min(1.0, kFullyLinedArea / std::max(area, 1.0)));
      const double target = density * double(faces[r].size()) * c.geometry.resolution;
      double lined = 0.0;
      const std::size_t trials = faces[r].size() / 8 + 30;
      for (std::size_t k = 0; k < trials && lined < target; ++k) {
        const cv::Point p = faces[r][static_cast<std::size_t>(
            random.integer(0, static_cast<std::int64_t>(faces[r].size()) - 1))];
        const Piece& piece = corridor ? pick(kCorridorPieces, kCorridorOdds, random)
                                      : pick(kRoomPieces, kRoomOdds, random);
        const std::size_t before = c.world->objects.size();
        if (against_wall(to_wall, p, static_cast<int>(r), piece))
          lined += (c.world->objects.size() > before) ? piece.length.min : 0.0;
      }
    }
  }

  // Tables with chairs in rooms, shelf rows in halls, where `passage` stays free around them.
  void stand_free(const WorldRegion& region, int r, const cv::Mat& clearance) {
    const GridGeometry& g = c.geometry;
    const bool hall = region.kind == "hall";
    const int count =
        std::clamp(static_cast<int>(region.area / (hall ? 150.0 : 40.0)), 1, hall ? 6 : 3);
    for (int k = 0; k < count; ++k) {
      for (int attempt = 0; attempt < 40; ++attempt) {
        const Eigen::Vector2d p(random.uniform(region.box.min().x(), region.box.max().x()),
                                random.uniform(region.box.min().y(), region.box.max().y()));
        const cv::Point px = pixel_of(g, p);
        if (!is_set(c.solids.inside, px) || c.rooms.labels.at<int>(px) != r)
          continue;
        const Eigen::Vector2d u = random.bernoulli(0.5) ? axis : left_of(axis);
        const double length = hall ? random.uniform(2.5, 5.0) : random.uniform(0.8, 2.0);
        const double depth = hall ? random.uniform(0.45, 0.6) : random.uniform(0.7, 1.0);
        if (clearance.at<float>(px) * g.resolution < length / 2 + o.passage)
          continue;
        const bool round = !hall && random.bernoulli(0.4);
        const auto outline =
            round ? circle_outline(p, depth / 2) : oriented_box(p, u, length, depth);
        if (!fits(outline, r))
          continue;
        place(hall ? "shelf" : "table", outline, r, p, u, round ? depth : length, depth);
        if (!hall) {
          const Eigen::Vector2d v = left_of(u);
          for (const double side : {-1.0, 1.0}) {
            const Eigen::Vector2d seat = p + v * side * (depth / 2 + 0.3);
            const auto chair = oriented_box(seat, u, 0.44, 0.44);
            if (random.bernoulli(0.8) && fits(chair, r))
              place("chair", chair, r, seat, u, 0.44, 0.44);
          }
        }
        break;
      }
    }
  }
};

}  // namespace

void furnish(WorldCanvas& c, double main_angle, const PlanWorldOptions& o, Random& random) {
  const cv::Mat before = c.reachable_space();
  Furnisher f{c, o, random, {std::cos(main_angle), std::sin(main_angle)}, {}, {}, {}};
  f.keep_free = cv::Mat(c.solid.size(), CV_8UC1, cv::Scalar(0));
  f.taken = cv::Mat(c.solid.size(), CV_8UC1, cv::Scalar(0));
  for (const Opening& op : c.rooms.openings) {
    if (op.bounded) {
      fill_outline(f.keep_free, c.geometry,
                   circle_outline(op.centre, op.width() / 2 + o.door_keep_free, 24));
    }
  }
  cv::bitwise_not(c.solid, f.free);
  cv::bitwise_and(f.free, c.solids.inside, f.free);
  cv::Mat blocked;
  cv::bitwise_not(f.free, blocked);
  f.line_walls(distance_to(blocked));
  // Free-standing pieces keep `passage` from walls and wall-lined pieces.
  cv::bitwise_not(f.free, blocked);
  const cv::Mat room_around = distance_to(blocked);
  for (std::size_t r = 0; r < c.rooms.regions.size(); ++r) {
    const WorldRegion& region = c.rooms.regions[r];
    if (region.kind != "corridor" && region.area >= 9.0)
      f.stand_free(region, static_cast<int>(r), room_around);
  }
  // Pieces between the robot and space it reached before them go again.
  std::vector<char> piece(c.world->objects.size());
  for (std::size_t k = 0; k < piece.size(); ++k)
    piece[k] = c.world->objects[k].kind == SurfaceKind::furniture;
  c.unblock(before, -1, [&](std::size_t k) { return piece[k] != 0; });
}

}  // namespace floorgrid::plan_world
