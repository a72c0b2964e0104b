// The server's JSON API (`floorgrid serve`): every call resolves to the parsed answer or throws
// an Error carrying the server's own {"error": message}.

async function request(method, path, body) {
  const init = { method, headers: {} };
  if (body !== undefined) {
    init.headers['Content-Type'] = 'application/json';
    init.body = JSON.stringify(body);
  }
  let response;
  try {
    response = await fetch(path, init);
  } catch (error) {
    throw new Error(`${method} ${path}: the server does not answer (${error.message})`);
  }
  const text = await response.text();
  let answer = null;
  try {
    answer = text ? JSON.parse(text) : null;
  } catch {
    answer = null;
  }
  if (!response.ok) {
    const message = answer && answer.error ? answer.error : `HTTP ${response.status}`;
    const error = new Error(`${method} ${path}: ${message}`);
    error.status = response.status;
    throw error;
  }
  return answer;
}

export const api = {
  info: () => request('GET', '/api/info'),
  /// Maps points [[x,y] or [x,y,theta], ...] from 'plan' or 'grid' to the other map.
  map: (from, points) => request('POST', '/api/map', { from, points }),
  robotPose: () => request('GET', '/api/robot_pose'),
  pairs: (withBase) => request('GET', withBase ? '/api/pairs?base=1' : '/api/pairs'),
  addPair: (plan, grid) => request('POST', '/api/pairs', { plan, grid }),
  deletePair: (id) => request('DELETE', `/api/pairs/${encodeURIComponent(id)}`),
  fit: (model) => request('POST', '/api/fit', { model }),
  heatmap: () => request('GET', '/api/heatmap'),
  /// Zones {geojson (object or a file's text), file?, kind, margin_sigma, speed_percent?}
  /// mapped onto the gridmap with the mask's picture; zonesNav2: the mask's nav2 files.
  zones: (body) => request('POST', '/api/zones', body),
  zonesNav2: (body) => request('POST', '/api/zones/nav2', body),
  /// Waypoints {geojson or csv, file?} mapped onto the gridmap, with the nav2 files.
  waypoints: (body) => request('POST', '/api/waypoints', body),
};
