// geotex workbench: the page of `geotex view` (view/README.md is the contract with the server).
// Plain script, no build step: three.js r111 and its OrbitControls are loaded before it as
// globals (THREE, THREE.OrbitControls), served by geotex itself so that it works offline.
'use strict';

(function () {
    // ---- state ---------------------------------------------------------------------------

    const state = {
        token: '',
        session: null,
        objects: [],          // GET /api/objects, the words updated by previews
        features: null,       // GET /api/features: {id: {texels: [], textures: []}}
        savedConcepts: [],    // GET /api/dictionary concepts: the file as last saved
        concepts: [],         // the concepts after the pending edits (previewed)
        edits: [],            // every edit since the last save, sent whole with each preview
        changed: [],          // the `changed` list of the last preview
        problems: [],         // the problems of the last preview (422), shown with their place
        marks: [],            // fitting examples: {object, texture, concept, yes}
        proposal: null,       // the last answer of POST /api/fit
        object: null,         // GET /api/objects/ID of the open object
        mesh: null,           // the parsed GTXM of the open object
        selectedTexel: null,  // texel pinned by a click (hover shows others while null)
        selectedTexture: null, // texture chosen in the legend
        view: null,           // the three.js objects of the 3D view
    };

    const NO_TEXEL_GREY = [0.62, 0.62, 0.62];
    const $ = (sel) => document.querySelector(sel);

    // Tests wait for this: true once the current view has drawn its first frame.
    window.geotexReady = false;

    // ---- HTTP ----------------------------------------------------------------------------

    // The token comes from the meta tag the server fills in; with `--host` the first URL also
    // carries ?token=, which wins because it is what the user was given.
    function readToken() {
        const fromUrl = new URLSearchParams(location.search).get('token');
        const meta = document.querySelector('meta[name="geotex-token"]');
        return fromUrl || (meta ? meta.content : '');
    }

    async function request(method, path, body) {
        const headers = { 'X-Geotex-Token': state.token };
        const init = { method, headers };
        if (body !== undefined) {
            headers['Content-Type'] = 'application/json';
            init.body = JSON.stringify(body);
        }
        const response = await fetch(path, init);
        return response;
    }

    async function getJson(path) {
        const response = await request('GET', path);
        const data = await response.json();
        if (!response.ok) throw new Error(data.error || `${path}: HTTP ${response.status}`);
        return data;
    }

    async function postJson(path, body) {
        const response = await request('POST', path, body);
        let data = null;
        try {
            data = await response.json();
        } catch (e) {
            data = { error: `${path}: HTTP ${response.status}` };
        }
        return { status: response.status, data };
    }

    function setStatus(text, isError) {
        const el = $('#status');
        el.textContent = text;
        el.classList.toggle('error', !!isError);
    }

    // ---- small helpers -------------------------------------------------------------------

    function el(tag, attrs, ...children) {
        const node = document.createElement(tag);
        for (const [k, v] of Object.entries(attrs || {})) {
            if (v === null || v === undefined || v === false) continue;
            if (k === 'class') node.className = v;
            else if (k === 'text') node.textContent = v;
            else if (k.startsWith('on')) node.addEventListener(k.slice(2), v);
            else node.setAttribute(k, v === true ? '' : v);
        }
        for (const c of children) {
            if (c === null || c === undefined) continue;
            node.append(c instanceof Node ? c : document.createTextNode(String(c)));
        }
        return node;
    }

    function formatNumber(v) {
        if (v === null || v === undefined) return '—';
        if (typeof v !== 'number') return String(v);
        if (v === 0) return '0';
        const a = Math.abs(v);
        return a >= 1e4 || a < 1e-3 ? v.toExponential(3) : Number(v.toPrecision(4)).toString();
    }

    function conceptById(id) {
        return state.concepts.find((c) => c.id === id) || null;
    }

    // The label a concept shows: the dictionary's first language, as the server's words do.
    function conceptLabel(c) {
        if (!c) return '';
        if (c.label) return c.label;
        const langs = Object.keys(c.labels || {});
        const lang = langs.includes('en') ? 'en' : langs[0];
        return lang ? c.labels[lang] : c.id;
    }

    function hexToRgb(hex) {
        const n = parseInt(hex.slice(1), 16);
        return [((n >> 16) & 255) / 255, ((n >> 8) & 255) / 255, (n & 255) / 255];
    }

    // ---- routing -------------------------------------------------------------------------

    // `#/objects/ID` opens one object (a link a curator can send); anything else is the list.
    function route() {
        const m = location.hash.match(/^#\/objects\/(.+)$/);
        window.geotexReady = false;
        if (m) showObjectView(decodeURIComponent(m[1]));
        else showListView();
    }

    // ---- list view -----------------------------------------------------------------------

    function showListView() {
        disposeView();
        state.object = null;
        $('#object-view').hidden = true;
        $('#list-view').hidden = false;
        renderList();
        requestAnimationFrame(() => { window.geotexReady = true; });
    }

    function renderConceptFilter() {
        const select = $('#concept-filter');
        const current = select.value;
        const present = new Set();
        for (const o of state.objects) for (const c of o.concepts || []) present.add(c);
        const options = [...present].sort().map((id) => {
            const c = conceptById(id);
            return el('option', { value: id, text: c ? `${conceptLabel(c)} (${id})` : id });
        });
        select.replaceChildren(el('option', { value: '', text: 'any' }), ...options);
        select.value = present.has(current) ? current : '';
    }

    function objectMatches(o, text, concept) {
        if (concept && !(o.concepts || []).includes(concept)) return false;
        if (!text) return true;
        const t = text.toLowerCase();
        if (o.id.toLowerCase().includes(t)) return true;
        return (o.concepts || []).some((id) => {
            const c = conceptById(id);
            return id.includes(t) || (c && conceptLabel(c).toLowerCase().includes(t));
        });
    }

    function renderList() {
        const text = $('#filter').value.trim();
        const concept = $('#concept-filter').value;
        const changedObjects = new Set(state.changed.map((c) => c.object));
        const rows = [];
        let shown = 0;
        for (const o of state.objects) {
            if (!objectMatches(o, text, concept)) continue;
            shown++;
            const thumb = el('img', { class: 'thumb', alt: '', width: 64, height: 64, 'data-thumb': o.id });
            const words = (o.concepts || []).map((id) => {
                const c = conceptById(id);
                return el('span', { class: 'concept', 'data-concept': id, text: c ? conceptLabel(c) : id });
            });
            rows.push(el('tr', { 'data-object': o.id, class: changedObjects.has(o.id) ? 'changed' : null },
                el('td', {}, o.error ? null : thumb),
                el('td', {}, el('a', { href: `#/objects/${encodeURIComponent(o.id)}`, text: o.id })),
                el('td', { class: 'status' }, o.status, o.reannotate === false && !o.error
                    ? el('span', { class: 'hint', title: 'no geometry.cbor: its words do not follow the edits' }, ' (fixed words)') : null),
                el('td', { class: 'num texels' }, o.texels ?? '—'),
                el('td', { class: 'num textures' }, o.textures ?? '—'),
                el('td', {}, ...(o.error ? [el('span', { class: 'error', 'data-error': o.id, text: o.error })]
                    : o.status !== 'ok' && o.reason ? [el('span', { class: 'hint', text: o.reason }), ...words] : words))));
        }
        $('#objects tbody').replaceChildren(...rows);
        $('#list-count').textContent = `${shown} of ${state.objects.length} objects`;
        loadThumbnails();
    }

    // Thumbnails go through fetch so that they carry the token header. Only the rows in view
    // ask for theirs (a collection may hold thousands), four at a time so that the server
    // stays free for the curator's clicks.
    const thumbnailCache = new Map();
    const thumbnailQueue = [];
    let thumbnailWorkers = 0;
    const thumbnailObserver = new IntersectionObserver((entries) => {
        for (const e of entries) {
            if (!e.isIntersecting) continue;
            thumbnailObserver.unobserve(e.target);
            thumbnailQueue.push(e.target);
        }
        while (thumbnailWorkers < 4 && thumbnailQueue.length) fetchThumbnails();
    });

    function loadThumbnails() {
        thumbnailObserver.disconnect();
        thumbnailQueue.length = 0;
        for (const img of document.querySelectorAll('img[data-thumb]')) {
            if (thumbnailCache.get(img.dataset.thumb)) img.src = thumbnailCache.get(img.dataset.thumb);
            else thumbnailObserver.observe(img);
        }
    }

    async function fetchThumbnails() {
        thumbnailWorkers++;
        while (thumbnailQueue.length) {
            const img = thumbnailQueue.shift();
            const id = img.dataset.thumb;
            try {
                if (!thumbnailCache.has(id)) {
                    const r = await request('GET', `/api/objects/${encodeURIComponent(id)}/thumbnail.png`);
                    thumbnailCache.set(id, r.ok ? URL.createObjectURL(await r.blob()) : '');
                }
                if (thumbnailCache.get(id)) img.src = thumbnailCache.get(id);
            } catch (e) { /* a missing thumbnail leaves an empty cell */ }
        }
        thumbnailWorkers--;
    }

    // ---- object view ---------------------------------------------------------------------

    async function showObjectView(id) {
        $('#list-view').hidden = true;
        $('#object-view').hidden = false;
        $('#object-title').textContent = id;
        $('#legend').replaceChildren();
        $('#info').replaceChildren(el('p', { class: 'hint', text: 'Hover or click a face.' }));
        $('#object-error').hidden = true;
        $('#object-body').hidden = false;
        disposeView();
        state.selectedTexel = null;
        state.selectedTexture = null;
        setStatus(`loading ${id}…`);
        try {
            for (const k of Object.keys(timings)) delete timings[k];
            timings.start = performance.now();
            const [object, mesh] = await Promise.all([
                getJson(`/api/objects/${encodeURIComponent(id)}`),
                loadMesh(id),
            ]);
            if (location.hash !== `#/objects/${encodeURIComponent(id)}` &&
                location.hash !== `#/objects/${id}`) return;  // the user moved on meanwhile
            state.object = object;
            applyPreviewTextures();
            state.mesh = mesh;
            renderLegend();
            createView(mesh);
            setStatus(`${id}: ${mesh.numFaces.toLocaleString()} faces, ${object.texels.length} texels`);
        } catch (e) {
            $('#object-body').hidden = true;
            const err = $('#object-error');
            err.textContent = e.message;
            err.hidden = false;
            setStatus('');
            window.geotexReady = true;
        }
    }

    // ---- mesh loading (GTXM) -------------------------------------------------------------

    // Milliseconds from opening an object to each step, for the benchmark of issue 19
    // (a 1.3-million-face object on screen within 3 s): read by bench scripts and tests.
    const timings = {};
    window.geotexTimings = timings;
    const mark = (name) => {
        if (!(name in timings)) timings[name] = Math.round(performance.now() - timings.start);
    };

    async function loadMesh(id) {
        const response = await request('GET', `/api/objects/${encodeURIComponent(id)}/mesh`);
        if (!response.ok) {
            let message = `mesh: HTTP ${response.status}`;
            try { message = (await response.json()).error || message; } catch (e) { /* binary */ }
            throw new Error(message);
        }
        const buffer = await response.arrayBuffer();
        mark('transfer');
        const mesh = parseGtxm(buffer);
        mark('parse');
        return mesh;
    }

    // view/README.md, "GTXM": header, positions, indices, each face's texel, then each texel's
    // texture and depth, which are spread to per-face arrays here for the colour modes.
    function parseGtxm(buffer) {
        const view = new DataView(buffer);
        const magic = String.fromCharCode(view.getUint8(0), view.getUint8(1), view.getUint8(2), view.getUint8(3));
        if (magic !== 'GTXM') throw new Error('mesh: not a GTXM file');
        const version = view.getUint32(4, true);
        if (version !== 2) throw new Error(`mesh: GTXM version ${version}, expected 2`);
        const numVertices = view.getUint32(8, true);
        const numFaces = view.getUint32(12, true);
        const numTexels = view.getUint32(16, true);
        const expected = 20 + 12 * numVertices + 16 * numFaces + 8 * numTexels;
        if (buffer.byteLength !== expected) {
            throw new Error(`mesh: ${buffer.byteLength} bytes, expected ${expected}`);
        }
        // Every section is a multiple of 4 bytes long, so typed arrays can view it in place
        // (little-endian, as every browser's platform is).
        let offset = 20;
        const take = (Type, count) => {
            const a = new Type(buffer, offset, count);
            offset += 4 * count;
            return a;
        };
        const positions = take(Float32Array, 3 * numVertices);
        const indices = take(Uint32Array, 3 * numFaces);
        const faceTexel = take(Int32Array, numFaces);
        const texelTexture = take(Int32Array, numTexels);
        const texelDepth = take(Float32Array, numTexels);
        const faceTexture = new Int32Array(numFaces);
        const faceDepth = new Float32Array(numFaces);
        for (let f = 0; f < numFaces; f++) {
            const t = faceTexel[f];
            if (t >= numTexels) throw new Error(`mesh: face ${f} in texel ${t} of ${numTexels}`);
            faceTexture[f] = t < 0 ? -1 : texelTexture[t];
            faceDepth[f] = t < 0 ? NaN : texelDepth[t];
        }
        return {
            numVertices,
            numFaces,
            numTexels,
            positions,
            indices,
            faceTexel,
            faceTexture,
            faceDepth
        };
    }

    // Indexed geometry as the server sent it: a vertex belongs to the faces of one texel only
    // (view/README.md, "GTXM"), so a colour per vertex is a colour per texel, with no bleeding
    // across texel borders and no per-face copy of a million triangles. Normals are the
    // area-weighted means of the faces' normals: smooth shading on a texel, a crease on its
    // border, where the vertices are split.
    function buildGeometry(mesh) {
        const p = mesh.positions;
        const idx = mesh.indices;
        const nor = new Float32Array(3 * mesh.numVertices);
        for (let f = 0; f < mesh.numFaces; f++) {
            const a = 3 * idx[3 * f], b = 3 * idx[3 * f + 1], c = 3 * idx[3 * f + 2];
            const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
            const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
            // The cross product's length is twice the face's area: its weight.
            const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
            nor[a] += nx;
            nor[a + 1] += ny;
            nor[a + 2] += nz;
            nor[b] += nx;
            nor[b + 1] += ny;
            nor[b + 2] += nz;
            nor[c] += nx;
            nor[c + 1] += ny;
            nor[c + 2] += nz;
        }
        for (let v = 0; v < nor.length; v += 3) {
            const len = Math.hypot(nor[v], nor[v + 1], nor[v + 2]) || 1;
            nor[v] /= len;
            nor[v + 1] /= len;
            nor[v + 2] /= len;
        }
        const geometry = new THREE.BufferGeometry();
        geometry.setIndex(new THREE.BufferAttribute(idx, 1));
        geometry.setAttribute('position', new THREE.BufferAttribute(p, 3));
        geometry.setAttribute('normal', new THREE.BufferAttribute(nor, 3));
        // Bytes, not floats, for colours: a third of the memory on a million vertices.
        geometry.setAttribute(
            'color', new THREE.BufferAttribute(new Uint8Array(3 * mesh.numVertices), 3, true));
        geometry.computeBoundingSphere();
        return geometry;
    }

    // ---- colour modes --------------------------------------------------------------------

    // Distinct colours for neighbouring texel ids: hues a golden angle apart.
    function texelColour(id) {
        const c = new THREE.Color();
        c.setHSL((id * 0.618033988749895) % 1, 0.65, 0.55);
        return [c.r, c.g, c.b];
    }

    // A short viridis-like ramp: readable depth order, and no colour of it is a texture's grey.
    const DEPTH_RAMP = [[0.267, 0.005, 0.329], [0.231, 0.322, 0.545], [0.129, 0.569, 0.549],
        [0.365, 0.784, 0.388], [0.992, 0.906, 0.145]];
    function depthColour(t) {
        const x = Math.min(Math.max(t, 0), 1) * (DEPTH_RAMP.length - 1);
        const i = Math.min(Math.floor(x), DEPTH_RAMP.length - 2);
        const f = x - i;
        return [0, 1, 2].map((k) => DEPTH_RAMP[i][k] * (1 - f) + DEPTH_RAMP[i + 1][k] * f);
    }

    function depthRange(mesh) {
        let lo = Infinity, hi = -Infinity;
        for (const d of mesh.faceDepth) {
            if (Number.isFinite(d)) { lo = Math.min(lo, d); hi = Math.max(hi, d); }
        }
        return lo <= hi ? [lo, hi] : null;
    }

    // Returns a function face → [r, g, b] in 0..1 for the chosen mode.
    function faceColourFunction(mode, mesh) {
        if (mode === 'texel') {
            return (f) => (mesh.faceTexel[f] < 0 ? NO_TEXEL_GREY : texelColour(mesh.faceTexel[f]));
        }
        if (mode === 'depth') {
            const range = depthRange(mesh);
            const span = range && range[1] > range[0] ? range[1] - range[0] : 1;
            return (f) => {
                const d = mesh.faceDepth[f];
                return Number.isFinite(d) && range ? depthColour((d - range[0]) / span) : NO_TEXEL_GREY;
            };
        }
        const colours = new Map();
        for (const t of state.object.textures) colours.set(t.id, hexToRgb(t.colour));
        return (f) => colours.get(mesh.faceTexture[f]) || NO_TEXEL_GREY;
    }

    // The picked texel is drawn lighter so that the curator sees which faces the panel means;
    // a texture chosen in the legend keeps its colours while the rest fades.
    function paintColours() {
        const v = state.view;
        if (!v) return;
        const mesh = state.mesh;
        const mode = $('#colour-mode').value;
        const colourOf = faceColourFunction(mode, mesh);
        const attr = v.geometry.getAttribute('color');
        const out = attr.array;
        const picked = state.selectedTexel;
        const texture = state.selectedTexture;
        // Every face of a texel has the same colour, and the faces outside texels share grey:
        // the colour is worked out once per texel (slot texel + 1) and copied to the vertices.
        const palette = new Int16Array(3 * (mesh.numTexels + 1)).fill(-1);
        const idx = mesh.indices;
        for (let f = 0; f < mesh.numFaces; f++) {
            const slot = 3 * (mesh.faceTexel[f] + 1);
            if (palette[slot] < 0) {
                let [r, g, b] = colourOf(f);
                if (picked !== null && mesh.faceTexel[f] === picked) {
                    r = 0.5 + 0.5 * r;
                    g = 0.5 + 0.5 * g;
                    b = 0.5 + 0.5 * b;
                } else if (texture !== null && mesh.faceTexture[f] !== texture) {
                    // The other faces fade so that the chosen texture's texels stand out.
                    r = 0.75 + 0.25 * r;
                    g = 0.75 + 0.25 * g;
                    b = 0.75 + 0.25 * b;
                }
                palette[slot] = Math.round(r * 255);
                palette[slot + 1] = Math.round(g * 255);
                palette[slot + 2] = Math.round(b * 255);
            }
            for (let k = 3 * f; k < 3 * f + 3; k++) {
                const o = 3 * idx[k];
                out[o] = palette[slot];
                out[o + 1] = palette[slot + 1];
                out[o + 2] = palette[slot + 2];
            }
        }
        attr.needsUpdate = true;
        mark('colours');
        renderDepthScale(mode, mesh);
        requestRender();
    }

    function renderDepthScale(mode, mesh) {
        const span = $('#depth-scale');
        const range = mode === 'depth' ? depthRange(mesh) : null;
        span.textContent = range ? `depth ${formatNumber(range[0])} (dark) to ${formatNumber(range[1])} (yellow)` : '';
    }

    // ---- 3D view -------------------------------------------------------------------------

    function createView(mesh) {
        const container = $('#viewport');
        const width = container.clientWidth || 640;
        const height = container.clientHeight || 480;
        // preserveDrawingBuffer: the canvas can be read back (tests, screenshots) after a frame.
        // Multisampling doubles the first frame of a million faces where WebGL runs on the CPU
        // (SwiftShader, machines without a GPU): big meshes go without it.
        const renderer = new THREE.WebGLRenderer({ antialias: mesh.numFaces < 500000, preserveDrawingBuffer: true });
        renderer.setPixelRatio(window.devicePixelRatio || 1);
        renderer.setSize(width, height);
        renderer.setClearColor(0xffffff, 1);
        container.replaceChildren(renderer.domElement);

        const geometry = buildGeometry(mesh);
        mark('geometry');
        const material = new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide });
        const object = new THREE.Mesh(geometry, material);
        const scene = new THREE.Scene();
        scene.add(object);

        // A light at the camera: faces turned to the viewer show their colour unchanged
        // (ambient + direct = 1), so the colours on screen are those of the legend.
        const sphere = geometry.boundingSphere;
        const camera = new THREE.PerspectiveCamera(35, width / height, sphere.radius / 100, sphere.radius * 100);
        // Far enough for the bounding sphere to fit the narrower side of the viewport.
        const halfFov = (camera.fov / 2) * Math.PI / 180;
        const fit = Math.min(Math.tan(halfFov), Math.tan(halfFov) * camera.aspect);
        const distance = (sphere.radius * 1.08) / Math.sin(Math.atan(fit));
        camera.position.copy(sphere.center).add(new THREE.Vector3(0, 0, distance));
        camera.lookAt(sphere.center);
        scene.add(new THREE.AmbientLight(0xffffff, 0.35));
        const light = new THREE.DirectionalLight(0xffffff, 0.65);
        light.position.set(0, 0, 1);
        camera.add(light);
        scene.add(camera);

        const controls = new THREE.OrbitControls(camera, renderer.domElement);
        controls.target.copy(sphere.center);
        controls.update();
        controls.addEventListener('change', requestRender);

        state.view = { renderer, scene, camera, controls, geometry, material, object, frame: 0 };
        paintColours();
        attachPicking(renderer.domElement);
        window.addEventListener('resize', resizeView);
    }

    // Frames are drawn on demand (after a change), which keeps an idle page idle.
    function requestRender() {
        const v = state.view;
        if (!v || v.frame) return;
        v.frame = requestAnimationFrame(() => {
            v.frame = 0;
            v.renderer.render(v.scene, v.camera);
            if (!window.geotexReady) {
                // readPixels waits for the GPU: the frame is really drawn, not just queued.
                const gl = v.renderer.getContext();
                gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
                mark('first_frame');
                // From the page's own start: what a link opened in a new tab waits.
                timings.since_page_start = Math.round(performance.now());
                window.geotexReady = true;
            }
        });
    }

    function resizeView() {
        const v = state.view;
        if (!v) return;
        const container = $('#viewport');
        v.camera.aspect = container.clientWidth / container.clientHeight;
        v.camera.updateProjectionMatrix();
        v.renderer.setSize(container.clientWidth, container.clientHeight);
        requestRender();
    }

    function disposeView() {
        const v = state.view;
        if (!v) return;
        if (v.frame) cancelAnimationFrame(v.frame);
        v.controls.dispose();
        v.geometry.dispose();
        v.material.dispose();
        v.renderer.dispose();
        v.renderer.domElement.remove();
        window.removeEventListener('resize', resizeView);
        state.view = null;
        state.mesh = null;
    }

    // ---- picking -------------------------------------------------------------------------

    // The face under a canvas pixel (CSS pixels from the canvas's top-left corner), or null.
    function pickFace(x, y) {
        const v = state.view;
        if (!v) return null;
        const canvas = v.renderer.domElement;
        const ndc = new THREE.Vector2((x / canvas.clientWidth) * 2 - 1, -(y / canvas.clientHeight) * 2 + 1);
        const raycaster = new THREE.Raycaster();
        raycaster.setFromCamera(ndc, v.camera);
        const hits = raycaster.intersectObject(v.object);
        if (!hits.length) return null;
        const face = hits[0].faceIndex;
        return { face, texel: state.mesh.faceTexel[face], texture: state.mesh.faceTexture[face] };
    }
    window.geotexPick = pickFace;

    // A click that did not move the camera pins the texel under it; hovering shows texels
    // while none is pinned. Hover picks once the pointer rests, as a ray test is O(faces).
    function attachPicking(canvas) {
        let down = null;
        let hoverTimer = 0;
        canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
        canvas.addEventListener('pointerup', (e) => {
            if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;
            const r = canvas.getBoundingClientRect();
            const hit = pickFace(e.clientX - r.left, e.clientY - r.top);
            selectTexel(hit && hit.texel >= 0 ? hit.texel : null, hit);
        });
        canvas.addEventListener('pointermove', (e) => {
            if (state.selectedTexel !== null || e.buttons) return;
            clearTimeout(hoverTimer);
            hoverTimer = setTimeout(() => {
                if (state.selectedTexel !== null) return;  // a click pinned a texel meanwhile
                const r = canvas.getBoundingClientRect();
                const hit = pickFace(e.clientX - r.left, e.clientY - r.top);
                if (hit) renderInfo(hit);
            }, 120);
        });
    }

    function selectTexel(texel, hit) {
        state.selectedTexel = texel;
        state.selectedTexture = null;
        for (const li of document.querySelectorAll('#legend li.selected')) li.classList.remove('selected');
        paintColours();
        renderInfo(hit);
    }

    // ---- info panel ----------------------------------------------------------------------

    // The interval a value falls in: the server's answer for the saved dictionary; during a
    // preview, the previewed concept whose [lower, upper) holds it.
    function intervalOf(texel, feature) {
        if (!state.edits.length) return texel.interval ? texel.interval[feature] : null;
        const value = texel.features[feature];
        if (value === null || value === undefined) return null;
        const c = state.concepts.find((k) => k.feature === feature &&
            (k.lower === null || value >= k.lower) && (k.upper === null || value < k.upper));
        return c ? c.id : null;
    }

    function renderInfo(hit) {
        const info = $('#info');
        if (!hit) {
            info.replaceChildren(el('p', { class: 'hint', text: 'No face here.' }));
            return;
        }
        if (hit.texel < 0) {
            info.replaceChildren(el('p', { 'data-face': hit.face, text: `Face ${hit.face}: in no texel.` }));
            return;
        }
        const texel = state.object.texels.find((t) => t.id === hit.texel);
        const texture = state.object.textures.find((t) => t.id === (texel ? texel.texture : hit.texture));
        const parts = [el('p', { 'data-face': hit.face, 'data-texel': hit.texel },
            hit.face >= 0 ? `Face ${hit.face}, texel ${hit.texel}` : `Texel ${hit.texel}`)];
        if (texture) parts.push(textureSummary(texture, 'info-texture'));
        if (texel) {
            const rows = state.session.features.map((f) => {
                const cid = intervalOf(texel, f);
                const c = cid ? conceptById(cid) : null;
                // A break allowed after each underscore keeps long feature ids readable.
                return el('tr', { 'data-feature': f },
                    el('td', {}, f.replace(/_/g, '_\u200b')),
                    el('td', { class: 'num' }, formatNumber(texel.features[f])),
                    el('td', { class: 'num' }, formatNumber(texel.significance ? texel.significance[f] : null)),
                    el('td', { 'data-interval': cid || '' }, cid ? `${conceptLabel(c)}` : '—'));
            });
            parts.push(el('table', { class: 'texel-features' },
                el('thead', {}, el('tr', {}, el('th', {}, 'feature'), el('th', {}, 'value'),
                    el('th', { title: 'significance' }, 'signif.'), el('th', {}, 'interval'))),
                el('tbody', {}, ...rows)));
        }
        info.replaceChildren(...parts);
    }

    // ---- legend --------------------------------------------------------------------------

    function textureSummary(t, cls) {
        const changed = state.changed.some((c) => c.object === state.object.id && c.texture === t.id);
        return el('div', { class: cls + (changed ? ' changed' : ''), 'data-texture': t.id },
            el('span', { class: 'swatch', style: `background:${t.colour}`, 'data-colour': t.colour }),
            el('strong', {}, `texture ${t.id}`),
            ` ${t.orientation}, ${t.texels} texels`,
            el('div', { class: 'words' }, ...t.concepts.map((c) =>
                el('span', { class: 'concept', 'data-concept': c.id, title: `${c.feature} in [${formatNumber(c.lower)}, ${formatNumber(c.upper)})` }, conceptLabel(c))),
            ...(t.withheld || []).map((c) =>
                el('span', { class: 'concept withheld', 'data-concept': c.id, title: `withheld: ${c.feature}` }, conceptLabel(c)))));
    }

    function renderLegend() {
        const object = state.object;
        const items = object.textures.map((t) => {
            const li = el('li', { 'data-texture': t.id, class: t.id === state.selectedTexture ? 'selected' : null }, textureSummary(t, 'legend-texture'), markForm(object.id, t.id));
            li.querySelector('.legend-texture').addEventListener('click', () => selectTexture(t.id));
            return li;
        });
        if (!items.length) items.push(el('li', { class: 'hint', text: 'No texture.' }));
        $('#legend').replaceChildren(...items);
    }

    // A second click on the same texture shows the whole object again.
    function selectTexture(id) {
        state.selectedTexture = state.selectedTexture === id ? null : id;
        state.selectedTexel = null;
        for (const li of document.querySelectorAll('#legend li[data-texture]')) {
            li.classList.toggle('selected', Number(li.dataset.texture) === state.selectedTexture);
        }
        const t = state.object.textures.find((x) => x.id === state.selectedTexture);
        // The texture's words in the info panel, as a click on one of its faces shows them.
        $('#info').replaceChildren(t ? textureSummary(t, 'info-texture')
            : el('p', { class: 'hint', text: 'Hover or click a face.' }));
        paintColours();
    }

    // After a preview, the open object shows the previewed words.
    function applyPreviewTextures() {
        if (!state.object || !state.previewObjects) return;
        const p = state.previewObjects.find((o) => o.id === state.object.id);
        if (p) state.object.textures = p.textures;
    }

    // ---- fitting marks -------------------------------------------------------------------

    function markForm(objectId, textureId) {
        const select = el('select', { class: 'mark-concept', 'aria-label': 'concept' },
            el('option', { value: '', text: 'mark with…' }),
            ...state.concepts.map((c) => el('option', { value: c.id, text: `${c.feature}: ${conceptLabel(c)}` })));
        const add = (yes) => () => {
            if (!select.value) return;
            addMark({ object: objectId, texture: textureId, concept: select.value, yes });
        };
        return el('div', { class: 'mark-form' }, select,
            el('button', { type: 'button', class: 'mark-yes', onclick: add(true) }, 'yes'),
            el('button', { type: 'button', class: 'mark-no', onclick: add(false) }, 'no'));
    }

    function addMark(mark) {
        state.marks = state.marks.filter((m) => !(m.object === mark.object && m.texture === mark.texture && m.concept === mark.concept));
        state.marks.push(mark);
        renderMarks();
    }

    function renderMarks() {
        const items = state.marks.map((m, i) => el('li', { 'data-mark': `${m.object}:${m.texture}:${m.concept}` },
            `${m.object} texture ${m.texture} ${m.yes ? 'is' : 'is not'} ${m.concept} `,
            el('button', { type: 'button', title: 'remove', onclick: () => { state.marks.splice(i, 1); renderMarks(); } }, '×')));
        $('#marks').replaceChildren(...items);
        $('#propose').disabled = !state.marks.length;
    }

    async function proposeBounds() {
        setStatus('fitting…');
        const { status, data } = await postJson('/api/fit', { marks: state.marks });
        if (status !== 200) {
            setStatus(data.error || `fit: HTTP ${status}`, true);
            return;
        }
        state.proposal = data;
        $('#fit-edits').replaceChildren(...(data.edits.length ? data.edits.map((e) => el('li', { class: 'fit-edit' }, describeEdit(e)))
            : [el('li', { class: 'hint', text: 'No bound needs to move.' })]));
        $('#unsatisfied').replaceChildren(...data.unsatisfied.map((u) => el('li', { class: 'error', 'data-mark': `${u.object}:${u.texture}:${u.concept}` },
            `${u.object} texture ${u.texture} ${u.yes ? 'is' : 'is not'} ${u.concept}: ${u.reason}`)));
        $('#apply-fit').disabled = !data.edits.length;
        $('#proposal').hidden = false;
        setStatus(`fit: ${data.edits.length} edit(s), ${data.unsatisfied.length} mark(s) unsatisfied`);
    }

    function applyProposal() {
        if (!state.proposal) return;
        for (const e of state.proposal.edits) addEdit(e);
        preview();
    }

    // ---- editor: pending edits, preview, save --------------------------------------------

    function describeEdit(e) {
        return e.op === 'bound' ? `${e.concept} ${e.side} → ${e.value}` : `${e.concept} label (${e.lang}) → “${e.value}”`;
    }

    // A later edit of the same bound or label replaces the earlier one: the list stays the
    // curator's intent, not the history of a drag.
    function addEdit(edit) {
        const same = (e) => e.op === edit.op && e.concept === edit.concept &&
            (edit.op === 'bound' ? e.side === edit.side : e.lang === edit.lang);
        const i = state.edits.findIndex(same);
        if (i >= 0) state.edits[i] = edit;
        else state.edits.push(edit);
    }

    function renderEdits() {
        $('#edits').replaceChildren(...state.edits.map((e, i) => el('li', { class: 'edit' }, describeEdit(e), ' ',
            el('button', { type: 'button', title: 'undo this edit', onclick: () => { state.edits.splice(i, 1); preview(); } }, '×'))));
        $('#discard').disabled = !state.edits.length;
        const editable = state.session && state.session.dictionary.editable;
        // Edits with problems would be refused (422): fix or undo them first.
        $('#save').disabled = !editable || !state.edits.length || state.problems.length > 0;
    }

    function renderProblems(problems) {
        state.problems = problems;
        renderEdits();
        $('#problems').replaceChildren(...problems.map((p) => el('li', { class: 'error', 'data-line': p.line, 'data-column': p.column },
            `line ${p.line}, column ${p.column}: ${p.message}`)));
    }

    async function preview() {
        renderEdits();
        if (!state.edits.length) {
            resetToSaved();
            return;
        }
        setStatus('re-annotating…');
        const { status, data } = await postJson('/api/preview', { edits: state.edits });
        if (status === 422) {
            renderProblems(data.problems || []);
            setStatus(`${(data.problems || []).length} problem(s) in the edits`, true);
            return;
        }
        if (status !== 200) {
            setStatus(data.error || `preview: HTTP ${status}`, true);
            return;
        }
        renderProblems([]);
        state.concepts = data.concepts;
        state.previewObjects = data.objects;
        state.changed = data.changed;
        updateObjectWords(data.objects);
        afterDictionaryChange();
        setStatus(`preview: ${data.changed.length} texture(s) changed words`);
    }

    // The list's concepts follow the previewed words of each object's textures.
    function updateObjectWords(previewObjects) {
        const byId = new Map(previewObjects.map((o) => [o.id, o]));
        for (const o of state.objects) {
            const p = byId.get(o.id);
            if (!p) continue;
            const ids = new Set();
            for (const t of p.textures) for (const c of t.concepts) ids.add(c.id);
            o.concepts = [...ids].sort();
        }
    }

    function resetToSaved() {
        state.concepts = state.savedConcepts;
        state.previewObjects = null;
        state.changed = [];
        renderProblems([]);
        reloadAfterSave().catch((e) => setStatus(e.message, true));
    }

    function afterDictionaryChange() {
        applyPreviewTextures();
        renderChanges();
        renderFeatureEditors();
        renderConceptFilter();
        if (state.object) {
            renderLegend();
            if (state.selectedTexel !== null) renderInfo({ face: -1, texel: state.selectedTexel, texture: -1 });
        }
        if (!$('#list-view').hidden) renderList();
    }

    function renderChanges() {
        const n = state.changed.length;
        $('#changes').replaceChildren(n ? `${n} texture(s) changed words: ` : '',
            ...state.changed.map((c) => el('a', { href: `#/objects/${encodeURIComponent(c.object)}`, class: 'changed-link', title: `${c.before.join(', ')} → ${c.after.join(', ')}` },
                `${c.object}/${c.texture} `)));
    }

    async function save() {
        setStatus('saving…');
        const { status, data } = await postJson('/api/save', { edits: state.edits });
        if (status === 422) {
            renderProblems(data.problems || []);
            setStatus('not saved: the edits have problems', true);
            return;
        }
        if (status !== 200) {
            setStatus(data.error || `save: HTTP ${status}`, true);
            return;
        }
        state.edits = [];
        state.changed = [];
        state.previewObjects = null;
        renderEdits();
        $('#save-status').textContent = `saved version ${data.version}`;
        $('#save-status').dataset.version = data.version;
        await reloadAfterSave();
        setStatus(`saved version ${data.version}`);
    }

    // After a save (or a discard) the server's words are the truth again: fetch them.
    async function reloadAfterSave() {
        const [session, dictionary, objects] = await Promise.all([
            getJson('/api/session'), getJson('/api/dictionary'), getJson('/api/objects')]);
        state.session = session;
        state.savedConcepts = dictionary.concepts;
        state.concepts = dictionary.concepts;
        state.objects = objects;
        renderSession();
        if (state.object) {
            state.object = await getJson(`/api/objects/${encodeURIComponent(state.object.id)}`);
            paintColours();
        }
        afterDictionaryChange();
    }

    function discardEdits() {
        state.edits = [];
        preview();
    }

    // ---- editor: histograms and bounds ---------------------------------------------------

    function conceptsOfFeature(feature) {
        return state.concepts.filter((c) => c.feature === feature)
            .sort((a, b) => (a.lower === null ? -Infinity : a.lower) - (b.lower === null ? -Infinity : b.lower));
    }

    // The histogram's range: the values' range, so that bounds at ±∞ or far out do not
    // squash the data; bounds outside it are listed in the inputs only.
    function histogramRange(values) {
        let lo = Infinity, hi = -Infinity;
        for (const v of values) if (v !== null && Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
        if (!(lo <= hi)) return null;
        const pad = (hi - lo) * 0.05 || Math.abs(lo) * 0.05 || 1;
        return [lo - pad, hi + pad];
    }

    function renderFeatureEditors() {
        const container = $('#features');
        const open = new Set([...container.querySelectorAll('details[open]')].map((d) => d.dataset.feature));
        const sections = [];
        for (const feature of (state.session ? state.session.features : [])) {
            const concepts = conceptsOfFeature(feature);
            if (!concepts.length) continue;
            const canvas = el('canvas', { class: 'histogram', width: 360, height: 110, 'data-histogram': feature });
            const rows = concepts.map((c) => conceptRow(c));
            const details = el('details', { 'data-feature': feature, open: open.has(feature) },
                el('summary', {}, feature, ' ', el('span', { class: 'hint', text: concepts.map(conceptLabel).join(' · ') })),
                canvas, el('table', { class: 'bounds' }, el('tbody', {}, ...rows)));
            sections.push(details);
            drawHistogram(canvas, feature);
            attachBoundDrag(canvas, feature);
        }
        container.replaceChildren(...sections);
    }

    function conceptRow(c) {
        const lang = Object.keys(c.labels || {}).includes('en') ? 'en' : Object.keys(c.labels || {})[0] || 'en';
        const boundInput = (side) => {
            const value = c[side];
            // The YAML's own spelling of the bound when it still says the same number.
            const text = c[`${side}_text`];
            const shown = text && Number(text) === value ? text : String(value);
            return el('input', { type: 'text', class: 'bound', size: 7, 'data-bound': `${c.id}:${side}`,
                value: value === null ? (side === 'lower' ? '-∞' : '∞') : shown,
                disabled: value === null, title: value === null ? 'infinite: not editable here' : null,
                onchange: (e) => { addEdit({ op: 'bound', concept: c.id, side, value: e.target.value.trim() }); preview(); } });
        };
        const edited = state.edits.some((e) => e.concept === c.id);
        return el('tr', { 'data-concept': c.id, class: edited ? 'edited' : null },
            el('td', {}, boundInput('lower')),
            el('td', {}, boundInput('upper')),
            el('td', {}, el('input', { type: 'text', class: 'label', 'data-label': `${c.id}:${lang}`,
                value: (c.labels || {})[lang] || '', title: `${c.id} (line ${c.line})`,
                onchange: (e) => { addEdit({ op: 'label', concept: c.id, lang, value: e.target.value }); preview(); } })));
    }

    function drawHistogram(canvas, feature, dragged) {
        const ctx = canvas.getContext('2d');
        const w = canvas.width, h = canvas.height;
        ctx.clearRect(0, 0, w, h);
        const values = state.features ? state.features[feature] : null;
        const all = values ? values.texels.concat(values.textures) : [];
        const range = histogramRange(all);
        canvas.range = range;
        if (!range) {
            ctx.fillStyle = '#888';
            ctx.fillText('no values', 8, 20);
            return;
        }
        const x = (v) => ((v - range[0]) / (range[1] - range[0])) * w;
        const bins = 40;
        const count = (list) => {
            const c = new Array(bins).fill(0);
            for (const v of list) {
                if (v === null || !Number.isFinite(v)) continue;
                c[Math.min(bins - 1, Math.floor(((v - range[0]) / (range[1] - range[0])) * bins))]++;
            }
            return c;
        };
        const texels = count(values.texels), textures = count(values.textures);
        const top = 14, base = h - 14;
        const maxT = Math.max(1, ...texels), maxX = Math.max(1, ...textures);
        // Texels and textures have different counts: each is scaled to its own maximum.
        for (let i = 0; i < bins; i++) {
            const bx = (i / bins) * w, bw = w / bins - 1;
            ctx.fillStyle = '#b8c7d9';
            const th = (texels[i] / maxT) * (base - top);
            ctx.fillRect(bx, base - th, bw, th);
            ctx.fillStyle = '#2f5d8a';
            const xh = (textures[i] / maxX) * (base - top) * 0.6;
            ctx.fillRect(bx + bw * 0.25, base - xh, bw * 0.5, xh);
        }
        ctx.fillStyle = '#555';
        ctx.font = '10px sans-serif';
        ctx.fillText(formatNumber(range[0]), 2, h - 2);
        const right = formatNumber(range[1]);
        ctx.fillText(right, w - ctx.measureText(right).width - 2, h - 2);
        // Bounds: each finite bound once (a shared one is the upper of one concept and the
        // lower of the next), labelled by the concept it opens.
        ctx.strokeStyle = '#c0392b';
        ctx.lineWidth = 2;
        for (const b of boundsOfFeature(feature)) {
            const v = dragged && dragged.key === b.key ? dragged.value : b.value;
            if (v < range[0] || v > range[1]) continue;
            ctx.beginPath();
            ctx.moveTo(x(v), top - 4);
            ctx.lineTo(x(v), base);
            ctx.stroke();
        }
        ctx.fillStyle = '#222';
        for (const c of conceptsOfFeature(feature)) {
            const lo = c.lower === null ? range[0] : Math.max(range[0], c.lower);
            const hi = c.upper === null ? range[1] : Math.min(range[1], c.upper);
            if (hi <= range[0] || lo >= range[1]) continue;
            const label = conceptLabel(c);
            const mid = (x(lo) + x(hi)) / 2;
            const tw = Math.min(ctx.measureText(label).width, x(hi) - x(lo) - 2);
            if (tw > 12) ctx.fillText(label, mid - tw / 2, 10, tw);
        }
    }

    // The distinct finite bounds of a feature; each names the edit that moves it.
    function boundsOfFeature(feature) {
        const out = [];
        const seen = new Set();
        for (const c of conceptsOfFeature(feature)) {
            for (const side of ['lower', 'upper']) {
                const v = c[side];
                if (v === null || seen.has(v)) continue;
                seen.add(v);
                out.push({ key: `${c.id}:${side}`, concept: c.id, side, value: v });
            }
        }
        return out;
    }

    // Dragging a bound line previews on release (one re-annotation per drag, not per pixel).
    function attachBoundDrag(canvas, feature) {
        let drag = null;
        const valueAt = (e) => {
            const r = canvas.getBoundingClientRect();
            const px = ((e.clientX - r.left) / r.width) * canvas.width;
            return canvas.range[0] + (px / canvas.width) * (canvas.range[1] - canvas.range[0]);
        };
        canvas.addEventListener('pointerdown', (e) => {
            if (!canvas.range) return;
            const r = canvas.getBoundingClientRect();
            const tolerance = (6 / r.width) * (canvas.range[1] - canvas.range[0]);
            const v = valueAt(e);
            let best = null;
            for (const b of boundsOfFeature(feature)) {
                if (Math.abs(b.value - v) <= tolerance && (!best || Math.abs(b.value - v) < Math.abs(best.value - v))) best = b;
            }
            if (!best) return;
            drag = { key: best.key, concept: best.concept, side: best.side, value: best.value };
            canvas.setPointerCapture(e.pointerId);
        });
        canvas.addEventListener('pointermove', (e) => {
            if (!drag) return;
            drag.value = valueAt(e);
            drawHistogram(canvas, feature, drag);
            const input = document.querySelector(`input[data-bound="${drag.key}"]`);
            if (input) input.value = Number(drag.value.toPrecision(4)).toString();
        });
        canvas.addEventListener('pointerup', () => {
            if (!drag) return;
            const value = Number(drag.value.toPrecision(4)).toString();
            addEdit({ op: 'bound', concept: drag.concept, side: drag.side, value });
            drag = null;
            preview();
        });
    }

    // ---- start ---------------------------------------------------------------------------

    function renderSession() {
        const s = state.session;
        $('#path').textContent = s.path;
        const d = s.dictionary;
        $('#dictionary-info').textContent = `dictionary ${d.id} ${d.version}` +
            (d.file ? ` (${d.file})` : ' (bundled, read-only)');
        $('#dictionary-info').dataset.version = d.version;
        $('#save').title = d.editable ? '' : 'read-only: start geotex view with --dictionary FILE to save';
        renderEdits();
    }

    async function start() {
        state.token = readToken();
        $('#filter').addEventListener('input', renderList);
        $('#concept-filter').addEventListener('change', renderList);
        $('#colour-mode').addEventListener('change', paintColours);
        $('#save').addEventListener('click', save);
        $('#discard').addEventListener('click', discardEdits);
        $('#propose').addEventListener('click', proposeBounds);
        $('#apply-fit').addEventListener('click', applyProposal);
        try {
            const [session, objects, dictionary, features] = await Promise.all([
                getJson('/api/session'), getJson('/api/objects'), getJson('/api/dictionary'), getJson('/api/features')]);
            state.session = session;
            state.objects = objects;
            state.savedConcepts = dictionary.concepts;
            state.concepts = dictionary.concepts;
            state.features = features;
            renderSession();
            renderProblems(dictionary.problems || []);
            renderConceptFilter();
            renderFeatureEditors();
        } catch (e) {
            setStatus(e.message, true);
            window.geotexReady = true;
            return;
        }
        window.addEventListener('hashchange', route);
        route();
    }

    start();
})();
