// Small pure helpers: angles, turns, the mapping's local Jacobian and the goal's ROS 2 text.

/// Wraps an angle to (-pi, pi].
export function wrapAngle(theta) {
  let t = theta % (2 * Math.PI);
  if (t > Math.PI) t -= 2 * Math.PI;
  if (t <= -Math.PI) t += 2 * Math.PI;
  return t;
}

export const degrees = (radians) => (radians * 180) / Math.PI;

/// A number with a fixed count of decimals, '-0.000' shown as '0.000'.
export function fixed(value, decimals) {
  if (value === null || value === undefined || !Number.isFinite(value)) return '—';
  const text = value.toFixed(decimals);
  return /^-0\.?0*$/.test(text) ? text.slice(1) : text;
}

/// The point {x, y} turned by `angle` (radians, counterclockwise) about `centre`; `p` itself
/// when the angle is 0 (so an unturned frame gives back exactly what it was given).
export function rotateAbout(p, centre, angle) {
  if (angle === 0) return { x: p.x, y: p.y };
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  const dx = p.x - centre.x;
  const dy = p.y - centre.y;
  return { x: centre.x + c * dx - s * dy, y: centre.y + s * dx + c * dy };
}

/// The axis-aligned box [[xmin, ymin], [xmax, ymax]] around `bounds` turned by `angle` about
/// `centre`.
export function turnedBox(bounds, centre, angle) {
  const [[xmin, ymin], [xmax, ymax]] = bounds;
  const corners = [[xmin, ymin], [xmax, ymin], [xmax, ymax], [xmin, ymax]]
    .map(([x, y]) => rotateAbout({ x, y }, centre, angle));
  const xs = corners.map((p) => p.x);
  const ys = corners.map((p) => p.y);
  return [[Math.min(...xs), Math.min(...ys)], [Math.max(...xs), Math.max(...ys)]];
}

/// Determinant of a 2x2 matrix [[a, b], [c, d]] (negative: the mapping mirrors).
export const determinant = (J) => J[0][0] * J[1][1] - J[0][1] * J[1][0];

const mapped = (p) => p && p.x !== null && p.y !== null && p.x !== undefined && p.y !== undefined;

/// J_target_source from the answers for p, p+(d,0), p+(0,d): [[a, b], [c, d]] (columns: the
/// images of the source's unit x and y steps), or null when a point did not map.
export function jacobianFromSteps(p0, px, py, step) {
  if (!mapped(p0) || !mapped(px) || !mapped(py)) return null;
  return [[(px.x - p0.x) / step, (py.x - p0.x) / step],
          [(px.y - p0.y) / step, (py.y - p0.y) / step]];
}

/// Local scale of a mapping (mean stretch of the two steps), for zoom offsets.
export function localScale(J) {
  const sx = Math.hypot(J[0][0], J[1][0]);
  const sy = Math.hypot(J[0][1], J[1][1]);
  return (sx + sy) / 2;
}

/// Polygon [[x, y], ...] around `centre` that the mapping sends onto a circle of `radius`
/// around the image point: centre + J^-1 * radius * (cos t, sin t). Null when J is singular.
export function preimageEllipse(centre, J, radius, vertices = 64) {
  const det = determinant(J);
  if (!Number.isFinite(det) || Math.abs(det) < 1e-9) return null;
  const inv = [[J[1][1] / det, -J[0][1] / det], [-J[1][0] / det, J[0][0] / det]];
  const points = [];
  for (let i = 0; i < vertices; i++) {
    const t = (2 * Math.PI * i) / vertices;
    const u = radius * Math.cos(t);
    const v = radius * Math.sin(t);
    points.push([centre.x + inv[0][0] * u + inv[0][1] * v, centre.y + inv[1][0] * u + inv[1][1] * v]);
  }
  return points;
}

/// Yaw-only quaternion (z, w) of a heading.
export function yawQuaternion(theta) {
  return { z: Math.sin(theta / 2), w: Math.cos(theta / 2) };
}

function poseFields(pose) {
  const q = yawQuaternion(pose.theta);
  return {
    x: fixed(pose.x, 3), y: fixed(pose.y, 3), qz: fixed(q.z, 4), qw: fixed(q.w, 4),
  };
}

/// geometry_msgs/PoseStamped as YAML, in the gridmap's frame 'map'.
export function poseStampedYaml(pose) {
  const f = poseFields(pose);
  return [
    'header:',
    '  frame_id: map',
    'pose:',
    `  position: {x: ${f.x}, y: ${f.y}, z: 0.0}`,
    `  orientation: {x: 0.0, y: 0.0, z: ${f.qz}, w: ${f.qw}}`,
  ].join('\n');
}

/// One line that sends the goal to Nav2.
export function ros2GoalCommand(pose) {
  const f = poseFields(pose);
  return 'ros2 topic pub --once /goal_pose geometry_msgs/msg/PoseStamped ' +
    `"{header: {frame_id: map}, pose: {position: {x: ${f.x}, y: ${f.y}, z: 0.0}, ` +
    `orientation: {x: 0.0, y: 0.0, z: ${f.qz}, w: ${f.qw}}}}"`;
}
