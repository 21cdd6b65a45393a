// The one entry of the vendored three.js bundle: the parts of three.js's core
// that crates/armkit-view/assets/viewer.js uses, and OrbitControls, exposed
// as the global `THREE` (a classic script, so that a report opened from
// file:// loads it: browsers refuse ES-module imports there). Only what is
// named here is bundled; a viewer change that needs another class adds it.
import {
  AmbientLight, AxesHelper, BoxGeometry, BufferAttribute, BufferGeometry,
  CanvasTexture, CapsuleGeometry, Color, CylinderGeometry, DirectionalLight,
  DoubleSide, GridHelper, Group, HemisphereLight, Line, LineBasicMaterial,
  Matrix4, Mesh, MeshStandardMaterial, PerspectiveCamera, Quaternion, Scene,
  SphereGeometry, Sprite, SpriteMaterial, Vector3, WebGLRenderer, REVISION,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

window.THREE = {
  AmbientLight, AxesHelper, BoxGeometry, BufferAttribute, BufferGeometry,
  CanvasTexture, CapsuleGeometry, Color, CylinderGeometry, DirectionalLight,
  DoubleSide, GridHelper, Group, HemisphereLight, Line, LineBasicMaterial,
  Matrix4, Mesh, MeshStandardMaterial, PerspectiveCamera, Quaternion, Scene,
  SphereGeometry, Sprite, SpriteMaterial, Vector3, WebGLRenderer, REVISION,
  OrbitControls,
};
