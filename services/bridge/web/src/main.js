// Entry point: wires the Foxglove client to the 3D stage and the panels, and publishes window.twinslamView (counts
// for a test's wait condition and for diagnostics; what is shown is judged from pixels, not from these numbers).
import { Box3 } from 'three';
import { COLORS } from './colors.js';
import { FoxgloveClient, socketUrl } from './foxglove_client.js';
import { routeTopic } from './messages.js';
import { Panels } from './panels.js';
import { Stage } from './scene.js';
import { Tiles } from './tiles.js';
import { Vehicles } from './vehicles.js';

const stage = new Stage(document.getElementById('view'));
const tiles = new Tiles(stage.scene);
const vehicles = new Vehicles(stage.scene, stage.resolution);
const panels = new Panels(document.getElementById('panel'));

for (const swatch of document.querySelectorAll('[data-color]')) {
  swatch.style.background = COLORS[swatch.dataset.color];
}

const view = {
  state: 'connecting',
  tiles: 0,
  triangles: 0,
  messages: 0,
  channels: [],
  poses: {}, // vehicle -> {estimate, truth, gnss}
  landmarks: {}, // vehicle -> {landmarks, registered}
  registrations: {}, // vehicle -> count
  services: 0,
  frames: 0,
  renderedMessages: 0, // messages reflected in the last rendered frame
  lastError: '',
};
window.twinslamView = view;

function frameSize() {
  const box = stage.framed ?? tiles.bounds;
  return box.isEmpty() ? 40 : Math.max(box.max.x - box.min.x, box.max.y - box.min.y);
}

function onMessage(channel, msg) {
  view.messages += 1;
  const { vehicle, kind } = routeTopic(channel.topic);
  try {
    if (kind === '/twin/tiles') {
      tiles.apply(msg);
    } else if (kind === '/services') {
      panels.addService(msg);
    } else if (vehicle !== null) {
      const v = vehicles.get(vehicle);
      switch (kind) {
        case 'estimate/path':
        case 'truth/path':
        case 'gnss/path':
          v.setPath(kind, msg);
          break;
        case 'estimate/pose':
          v.setPose(msg, frameSize());
          break;
        case 'gnss':
          v.gnss = msg; // shown as text only: a lat/lon has no place in W without the dataset origin
          break;
        case 'landmarks':
        case 'landmarks/registered':
          v.setCloud(kind, msg);
          break;
        case 'registration':
          panels.addRegistration(vehicle, msg);
          view.registrations[vehicle] = (view.registrations[vehicle] || 0) + 1;
          break;
        default:
          return;
      }
    } else {
      return; // a JSON channel this view does not draw
    }
  } catch (err) {
    // One malformed message must not stop the view; the last error is kept for diagnostics.
    view.lastError = `${channel.topic}: ${err?.message ?? err}`;
    console.warn(view.lastError);
    return;
  }
  scheduleUpdate();
}

// Messages arrive in bursts (a late subscriber gets every latched tile at once): the scene bounds, panels and the
// frame are refreshed at most every 200 ms.
let updateTimer = null;
function scheduleUpdate() {
  if (updateTimer) return;
  updateTimer = setTimeout(() => {
    updateTimer = null;
    const content = new Box3().union(tiles.bounds).union(vehicles.bounds());
    stage.frame(content);
    panels.flush(vehicles);
    refreshCounts();
    stage.requestRender();
  }, 200);
}

function refreshCounts() {
  view.tiles = tiles.count;
  view.triangles = tiles.triangles;
  for (const v of vehicles.byId.values()) {
    view.poses[v.id] = { estimate: v.counts['estimate/path'], truth: v.counts['truth/path'], gnss: v.counts['gnss/path'] };
    view.landmarks[v.id] = { landmarks: v.counts.landmarks, registered: v.counts['landmarks/registered'] };
  }
  view.services = panels.services.size;
}

// The count of messages drawn is taken when the frame is drawn, so a test can wait for a frame showing its data.
stage.beforeRender.push(() => {
  view.renderedMessages = view.messages;
  view.frames = stage.frames + 1;
});

const client = new FoxgloveClient(socketUrl(window.location), {
  onState: (s) => {
    view.state = s.state;
    panels.setConnection(s);
  },
  onChannels: (channels) => {
    view.channels = channels.map((c) => c.topic).sort();
    document.getElementById('channels').textContent = `${channels.length} JSON channels`;
    document.getElementById('channels').title = view.channels.join('\n');
  },
  onServerStatus: (s) => panels.setServerStatus(s),
  onMessage,
});
client.start();
panels.flush(vehicles);
stage.requestRender();
