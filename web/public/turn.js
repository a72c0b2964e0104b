// "turned like the plan": a robot's gridmap is usually turned arbitrarily against the building's
// floorplan. Measured through the API, alpha is the angle of the plan's x axis in the gridmap's
// frame at the plan's centre; the gridmap view drawn turned by -alpha shows the building at the
// plan's angle. Only a drawing: everything sent to the API stays in the gridmap's own frame.
import { degrees, determinant, fixed, jacobianFromSteps } from './geometry.js';

const L = window.L;
const MIN_TURN = (5 * Math.PI) / 180;  // on by default above this

/// {alpha, reason}: alpha (radians) from POST /api/map of the plan's centre and the centre plus
/// 1 m along x and along y; reason (alpha null) says why no turn makes the maps alike.
export async function measureTurn(api, info) {
  const [[xmin, ymin], [xmax, ymax]] = info.plan.bounds;
  const x = (xmin + xmax) / 2;
  const y = (ymin + ymax) / 2;
  let answer;
  try {
    answer = await api.map('plan', [[x, y], [x + 1, y], [x, y + 1]]);
  } catch (error) {
    return { alpha: null, reason: `the turn could not be measured: ${error.message}` };
  }
  const [p0, px, py] = answer.points;
  const J = jacobianFromSteps(p0, px, py, 1);
  if (!J) return { alpha: null, reason: `the plan's centre does not map to the gridmap (${p0.flag})` };
  if (!(determinant(J) > 0)) {
    return { alpha: null, reason: "the mapping mirrors the plan at its centre (the Jacobian's determinant is " +
                                  `${fixed(determinant(J), 3)}): no turn makes the two maps alike` };
  }
  return { alpha: Math.atan2(px.y - p0.y, px.x - p0.x), reason: null };
}

/// The gridmap pane's checkbox: on by default when the turn is over 5 degrees, then as the
/// operator sets it; disabled and off, with the reason as its tooltip, while there is no turn to
/// offer.
export class TurnControl {
  /// `measured`: measureTurn's answer. attach() gives it the gridmap's view.
  constructor({ api, status, measured }) {
    this.view = null;
    this.api = api;
    this.status = status;
    this.checkbox = document.getElementById('turn-like-plan');
    this.label = this.checkbox.closest('label');
    this.angle = document.getElementById('turn-angle');
    this.axes = axesControl();
    this.chosen = null;  // the operator's choice, once made
    this.setMeasured(measured);
    this.checkbox.addEventListener('change', () => {
      this.chosen = this.checkbox.checked;
      this.apply();
    });
  }

  /// The gridmap's view, made with the wanted turn.
  attach(view) {
    this.view = view;
    this.showAxes();
  }

  showAxes() {
    const turn = this.wanted();
    if (turn === 0) this.axes.remove();
    else this.axes.addTo(this.view.map).setTurn(turn);
  }

  /// The turn to draw the gridmap with now: alpha when on, else 0.
  wanted() {
    return this.checkbox.checked && this.alpha !== null ? this.alpha : 0;
  }

  setMeasured({ alpha, reason }) {
    this.alpha = alpha;
    this.reason = reason;
    this.checkbox.disabled = alpha === null;
    this.checkbox.checked = alpha !== null && (this.chosen ?? Math.abs(alpha) > MIN_TURN);
    this.angle.textContent = alpha === null ? '' : `${fixed(degrees(-alpha), 0)}°`;
    this.label.title = alpha === null ? `not available: ${reason}`
      : `draw the gridmap turned by ${fixed(degrees(-alpha), 1)}° so that the plan's x axis is horizontal ` +
        'on both maps (goals, poses and pairs stay in the gridmap\'s frame)';
  }

  /// Draws the gridmap with the wanted turn; resolves when its pictures are redrawn.
  apply() {
    this.showAxes();
    this.drawn = this.view.setTurn(this.wanted()).catch((error) => this.status(error.message, 'error'));
    return this.drawn;
  }

  /// Measures the turn again (after a refit) and redraws with it.
  async refresh(info) {
    this.setMeasured(await measureTurn(this.api, info));
    return this.apply();
  }
}

/// A small key in the gridmap's corner: its own x and y axes as drawn, when turned.
function axesControl() {
  const control = L.control({ position: 'topright' });
  control.onAdd = () => {
    const element = L.DomUtil.create('div', 'fg-axes');
    element.title = "the gridmap's own x and y axes (its poses and goals are in this frame)";
    element.innerHTML = '<svg xmlns="http://www.w3.org/2000/svg" width="64" height="64" viewBox="-32 -32 64 64">' +
      '<g class="fg-axes-turn">' +
      '<line x1="0" y1="0" x2="20" y2="0"/><path d="M 24 0 l -7 -4 l 0 8 Z"/>' +
      '<line x1="0" y1="0" x2="0" y2="-20"/><path d="M 0 -24 l -4 7 l 8 0 Z"/>' +
      '<text class="fg-axes-x" x="29" y="0">x</text><text class="fg-axes-y" x="0" y="-29">y</text>' +
      '</g></svg>';
    return element;
  };
  control.setTurn = (turn) => {
    const element = control.getContainer();
    const deg = degrees(turn);  // SVG turns clockwise on screen: -(-turn)
    element.querySelector('.fg-axes-turn').setAttribute('transform', `rotate(${deg})`);
    // The letters stay upright.
    for (const text of element.querySelectorAll('text')) {
      text.setAttribute('transform', `rotate(${-deg} ${text.getAttribute('x')} ${text.getAttribute('y')})`);
    }
    return control;
  };
  return control;
}
