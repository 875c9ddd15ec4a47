// The parts of three.js the page uses: build.sh bundles them, minified and
// tree-shaken, into three.min.js (committed; the page fetches nothing else).
export {
  ArrowHelper, AxesHelper, BoxGeometry, BufferAttribute, BufferGeometry, Color, ConeGeometry,
  CylinderGeometry, DirectionalLight, Euler, Group, HemisphereLight, Line, LineBasicMaterial,
  Mesh, MeshLambertMaterial, PerspectiveCamera, Quaternion, Scene, Vector3, WebGLRenderer,
} from 'three';
