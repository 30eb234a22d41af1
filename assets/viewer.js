// viaroad's viewer page (src/export/html.rs embeds this after the three.js bundle and the
// .glb): orbit controls, play/pause and a time slider; the page carries the legend (written
// from the file's asset.extras.legend). window.viaroad is the hook the browser test
// (tests/view_browser.rs) drives.
(function () {
  'use strict';
  const T = window.VIAROAD_THREE;
  const BACKGROUND = 0xf5f7fa;
  const api = { ready: false, error: null };
  window.viaroad = api;

  const container = document.getElementById('view');
  const legend = document.getElementById('legend');
  const playButton = document.getElementById('play');
  const slider = document.getElementById('time');
  const clock = document.getElementById('clock');

  const renderer = new T.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(container.clientWidth, container.clientHeight);
  container.appendChild(renderer.domElement);
  const scene = new T.Scene();
  scene.background = new T.Color(BACKGROUND);
  scene.add(new T.HemisphereLight(0xffffff, 0x8090a0, 2.0));
  const sun = new T.DirectionalLight(0xffffff, 1.5);
  sun.position.set(1, 2, 1.5);
  scene.add(sun);
  const camera = new T.PerspectiveCamera(45, container.clientWidth / container.clientHeight, 0.01, 1000);
  const controls = new T.OrbitControls(camera, renderer.domElement);

  let mixer = null;
  let duration = 0;
  let time = 0;
  let playing = true;
  let last = null;

  function render() {
    renderer.render(scene, camera);
  }

  function show(t) {
    time = Math.min(Math.max(t, 0), duration);
    // a repeating action wraps the end round to the start: stop a hair short of it
    if (mixer) mixer.setTime(Math.min(time, duration * (1 - 1e-7)));
    slider.value = duration > 0 ? Math.round((1000 * time) / duration) : 0;
    clock.textContent = time.toFixed(1) + ' s';
    render();
  }

  function setPlaying(p) {
    playing = p;
    playButton.textContent = p ? 'pause' : 'play';
    last = null;
  }

  function tick(now) {
    if (playing && mixer && duration > 0) {
      if (last !== null) show((time + (now - last) / 1000) % duration);
      last = now;
    } else {
      render();
    }
    requestAnimationFrame(tick);
  }

  function frame(root) {
    const box = new T.Box3().setFromObject(root);
    const centre = box.getCenter(new T.Vector3());
    const size = box.getSize(new T.Vector3()).length() || 1;
    camera.near = size / 1000;
    camera.far = size * 20;
    camera.position.copy(centre).add(new T.Vector3(0.45, 1.0, 0.75).multiplyScalar(size * 0.8));
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
  }

  // draws the objects under a node named in `names` (all with null), or all but them
  function select(names, keep) {
    scene.traverse((o) => {
      if (!(o.isMesh || o.isLine || o.isPoints)) return;
      if (!names) {
        o.visible = true;
        return;
      }
      let under = false;
      for (let p = o; p; p = p.parent) if (names.includes(p.name)) under = true;
      o.visible = under === keep;
    });
    render();
  }
  api.only = (names) => select(names, true);
  api.hide = (names) => select(names, false);
  api.setTime = function (f) {
    setPlaying(false);
    show(f * duration);
  };
  api.pixels = function () {
    const gl = renderer.getContext();
    const w = gl.drawingBufferWidth;
    const h = gl.drawingBufferHeight;
    const buf = new Uint8Array(w * h * 4);
    render();
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, buf);
    let s = '';
    for (let i = 0; i < buf.length; i += 0x8000) s += String.fromCharCode.apply(null, buf.subarray(i, i + 0x8000));
    return { width: w, height: h, rgba: btoa(s) };
  };

  playButton.addEventListener('click', () => setPlaying(!playing));
  slider.addEventListener('input', () => {
    setPlaying(false);
    show((slider.value / 1000) * duration);
  });
  window.addEventListener('resize', () => {
    camera.aspect = container.clientWidth / container.clientHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(container.clientWidth, container.clientHeight);
    render();
  });

  const b64 = document.getElementById('viaroad-glb').textContent.trim();
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  new T.GLTFLoader().parse(
    bytes.buffer,
    '',
    (gltf) => {
      scene.add(gltf.scene);
      if (gltf.animations.length > 0) {
        mixer = new T.AnimationMixer(gltf.scene);
        const action = mixer.clipAction(gltf.animations[0]);
        action.setLoop(T.LoopRepeat, Infinity);
        action.play();
        duration = gltf.animations[0].duration;
      }
      frame(gltf.scene);
      show(0);
      api.ready = true;
      requestAnimationFrame(tick);
    },
    (err) => {
      api.error = String(err);
      const e = document.createElement('div');
      e.id = 'error';
      e.textContent = 'cannot show the model: ' + err;
      legend.appendChild(e);
      console.error(err);
    }
  );
})();
