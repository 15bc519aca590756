// The view's colours in one place: the 3D objects, the legend and the headless pixel test
// (tests/node/web_view.test.mjs) must agree on them. Saturated, far apart in hue, and far from the grey-blue
// buildings and the dark background, so each can be counted by pixel colour.
export const COLORS = {
  estimate: '#ff2d55',
  truth: '#30d158',
  gnss: '#0a84ff',
  landmarks: '#ffd60a',
  registered: '#bf5af2',
  pose: '#ffffff',
  tiles: '#aab4c6',
};
