// The parts of three.js the viewer page uses (src/export/viewer.js), bundled into one classic
// script so that the page works from file:// with no module loading: `npm run bundle-three`
// writes assets/three-bundle.min.js (the versions are pinned in package.json).
export {
  AnimationMixer,
  Box3,
  Color,
  DirectionalLight,
  GridHelper,
  HemisphereLight,
  LoopRepeat,
  PerspectiveCamera,
  Scene,
  Vector3,
  WebGLRenderer,
  REVISION,
} from 'three';
export { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
export { OrbitControls } from 'three/addons/controls/OrbitControls.js';
