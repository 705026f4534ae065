// The workbench of `geotex view` in a real browser (Debian's Chromium, headless, WebGL through
// SwiftShader), driven by puppeteer-core. Run by tests/workbench_test.sh, which starts the
// server on a batch output and checks the saved dictionary afterwards.
//
// Usage: node workbench.mjs URL OUTDIR RESULT.json [READONLY_URL]
//   URL     the address `geotex view` printed
//   OUTDIR  the batch output the server shows: the expectations come from its files
//           (summary.csv, objects/<id>/report.json), not from the page or the API
//   RESULT  where to write what the shell script checks next (the edits saved, the version)
//   READONLY_URL  a second server on the same output without --dictionary: previews work,
//           Save stays disabled
import fs from 'node:fs';
import path from 'node:path';
import { launchChromium } from './chromium.mjs';

const [url, outdir, resultFile, readOnlyUrl] = process.argv.slice(2);
if (!resultFile) {
    console.error('usage: node workbench.mjs URL OUTDIR RESULT.json');
    process.exit(1);
}
const base = url.replace(/#.*$/, '');
let failures = 0;
function check(what, ok, detail) {
    if (ok) return;
    failures++;
    console.log(`FAIL: ${what}${detail === undefined ? '' : `: ${typeof detail === 'string' ? detail : JSON.stringify(detail)}`}`);
}

// ---- what the batch output says (independent of the server) ------------------------------

function readSummary() {
    const lines = fs.readFileSync(path.join(outdir, 'summary.csv'), 'utf8').trim().split('\n');
    const header = lines[0].split(',');
    // Ids and counts here hold no comma or quote (the test names its objects).
    return lines.slice(1).map((l) => Object.fromEntries(l.split(',').map((v, i) => [header[i], v])));
}
const summary = readSummary();
// The objects whose report.json parses; the shell script damages one, which must show its error.
const reports = new Map();
const broken = [];
for (const row of summary) {
    try {
        reports.set(row.id, JSON.parse(fs.readFileSync(path.join(outdir, 'objects', row.id, 'report.json'), 'utf8')));
    } catch (e) {
        broken.push(row.id);
    }
}
// Chosen words of each texture: {texture id: [{concept, label, feature, value}]}.
function chosenWords(report) {
    return new Map(report.annotation.textures.map((t) => [t.texture, t.concepts]));
}

// ---- browser -----------------------------------------------------------------------------

const browser = await launchChromium();
const started = Date.now();
let lap = started;
function step(name) {
    const now = Date.now();
    console.log(`  ${name}: ${now - lap} ms`);
    lap = now;
}
try {
    const page = await browser.newPage();
    page.on('pageerror', (e) => check('no error in the page', false, e.message));
    await page.setViewport({ width: 1280, height: 800 });
    const ready = () => page.waitForFunction('window.geotexReady === true', { timeout: 30000 });
    const texts = (sel) => page.$$eval(sel, (els) => els.map((e) => e.textContent.trim()));

    // ---- the list: every object of summary.csv with its counts and a thumbnail ----------
    await page.goto(base + '#/');
    await ready();
    const rows = await page.$$eval('#objects tbody tr', (trs) => trs.map((tr) => ({
        id: tr.dataset.object,
        texels: tr.querySelector('.texels').textContent,
        textures: tr.querySelector('.textures').textContent,
    })));
    check('the list holds the objects of summary.csv in order', JSON.stringify(rows.map((r) => r.id)) ===
        JSON.stringify(summary.map((s) => s.id)), rows.map((r) => r.id));
    // Every object's counts are summary.csv's, a damaged one's too; an empty cell is a dash.
    const shown = (cell) => (cell === '' ? '—' : cell);
    for (const s of summary) {
        const r = rows.find((x) => x.id === s.id);
        check(`${s.id}: texel and texture counts of summary.csv`,
            r && r.texels === shown(s.texels) && r.textures === shown(s.textures), r);
    }
    for (const id of broken) {
        const error = await page.$eval(`#objects tr[data-object="${id}"]`, (tr) => {
            const e = tr.querySelector('[data-error]');
            return e ? e.textContent : null;
        });
        check(`${id} (damaged report.json) shows its error`, error && error.includes('report.json'), error);
    }
    await page.waitForFunction(() => [...document.querySelectorAll('img[data-thumb]')].every((i) => i.complete && i.naturalWidth > 0),
        { timeout: 20000 }).catch(() => {});
    const thumbSizes = await page.$$eval('img[data-thumb]', (imgs) => imgs.map((i) => `${i.naturalWidth}x${i.naturalHeight}`));
    check('every object but the damaged one has a 192x192 thumbnail', thumbSizes.length === reports.size && thumbSizes.every((s) => s === '192x192'), thumbSizes);

    step('list and thumbnails');
    // Filter by a concept that some objects carry and others do not, when there is one.
    const carriers = new Map();
    for (const [id, report] of reports) {
        for (const words of chosenWords(report).values()) for (const w of words) {
            if (!carriers.has(w.concept)) carriers.set(w.concept, new Set());
            carriers.get(w.concept).add(id);
        }
    }
    const filterConcept = [...carriers.keys()].sort().find((c) => carriers.get(c).size < reports.size) || [...carriers.keys()].sort()[0];
    await page.select('#concept-filter', filterConcept);
    const filtered = await page.$$eval('#objects tbody tr', (trs) => trs.map((tr) => tr.dataset.object));
    check(`filter by ${filterConcept} keeps the objects that carry it`,
        JSON.stringify(filtered) === JSON.stringify(summary.map((s) => s.id).filter((id) => carriers.get(filterConcept).has(id))), filtered);

    // ---- one object, opened by its link ------------------------------------------------
    // The object with the most textures: the colour checks below then mean the most.
    const target = summary.filter((s) => reports.has(s.id)).sort((a, b) => Number(b.textures) - Number(a.textures) || a.id.localeCompare(b.id))[0].id;
    const report = reports.get(target);
    const words = chosenWords(report);
    const page2 = await browser.newPage();
    page2.on('pageerror', (e) => check('no error in the page', false, e.message));
    await page2.setViewport({ width: 1280, height: 800 });
    await page.close();
    const p = page2;
    const t0 = Date.now();
    await p.goto(`${base}#/objects/${encodeURIComponent(target)}`);
    await p.waitForFunction('window.geotexReady === true', { timeout: 30000 });
    const openMs = Date.now() - t0;

    step('open the object');
    // The legend: every texture of report.json, its colour and its chosen words.
    const legend = await p.$$eval('#legend li[data-texture]', (lis) => lis.map((li) => ({
        id: Number(li.dataset.texture),
        colour: li.querySelector('.swatch').dataset.colour,
        words: [...li.querySelectorAll('.legend-texture .concept:not(.withheld)')].map((s) => s.textContent.trim()),
    })));
    check('legend lists the textures of report.json', JSON.stringify(legend.map((t) => [t.id, t.colour.toLowerCase()])) ===
        JSON.stringify(report.textures.map((t) => [t.id, t.colour.toLowerCase()])), legend);
    for (const t of report.textures) {
        const l = legend.find((x) => x.id === t.id);
        const expected = (words.get(t.id) || []).map((w) => w.label).sort();
        check(`legend texture ${t.id} shows its words`, l && JSON.stringify(l.words.slice().sort()) === JSON.stringify(expected),
            { shown: l && l.words, expected });
    }

    // ---- the screenshot shows the texture colours ----------------------------------------
    // A face turned to the viewer is drawn in its texture's colour (the light sits at the
    // camera); count, in the canvas's part of a screenshot, the pixels of each legend colour.
    const canvas = await p.$('#viewport canvas');
    const box = await canvas.boundingBox();
    const png = await p.screenshot({ clip: box, encoding: 'base64' });
    const colours = report.textures.map((t) => t.colour);
    const found = await p.evaluate(async (b64, hexes) => {
        const img = new Image();
        img.src = `data:image/png;base64,${b64}`;
        await img.decode();
        const c = document.createElement('canvas');
        c.width = img.width;
        c.height = img.height;
        const ctx = c.getContext('2d');
        ctx.drawImage(img, 0, 0);
        const data = ctx.getImageData(0, 0, c.width, c.height).data;
        const rgb = hexes.map((h) => [1, 3, 5].map((k) => parseInt(h.slice(k, k + 2), 16)));
        const near = (i, col) => Math.abs(data[i] - col[0]) <= 6 && Math.abs(data[i + 1] - col[1]) <= 6 && Math.abs(data[i + 2] - col[2]) <= 6;
        return rgb.map((col) => {
            let count = 0;
            let best = null;
            for (let y = 2; y < c.height - 2; y++) for (let x = 2; x < c.width - 2; x++) {
                const i = 4 * (y * c.width + x);
                if (!near(i, col)) continue;
                count++;
                // A click target: a pixel whose 5x5 neighbourhood has the colour too (inside a
                // face, not on an edge), the nearest to the centre (faces seen head-on).
                let inside = true;
                for (let dy = -2; dy <= 2 && inside; dy++) for (let dx = -2; dx <= 2 && inside; dx++) {
                    inside = near(4 * ((y + dy) * c.width + x + dx), col);
                }
                const d = Math.hypot(x - c.width / 2, y - c.height / 2);
                if (inside && (!best || d < best.d)) best = { x, y, d };
            }
            return { count, best };
        });
    }, png, colours);
    report.textures.forEach((t, i) => {
        check(`the screenshot shows texture ${t.id}'s colour ${t.colour}`, found[i].count >= 20, found[i].count);
    });

    step('screenshot colours');
    // ---- clicking a face of a texture shows that texture's words and the texel's values --
    const clickable = report.textures.map((t, i) => ({ t, at: found[i].best })).filter((x) => x.at);
    check('a face of some texture can be clicked', clickable.length > 0);
    if (clickable.length) {
        const { t, at } = clickable[0];
        await p.mouse.click(box.x + at.x, box.y + at.y);
        await p.waitForSelector('#info [data-texel]', { timeout: 5000 }).catch(() => {});
        const info = await p.evaluate(() => {
            const texel = document.querySelector('#info [data-texel]');
            const texture = document.querySelector('#info .info-texture');
            return {
                texel: texel ? Number(texel.dataset.texel) : null,
                texture: texture ? Number(texture.dataset.texture) : null,
                words: texture ? [...texture.querySelectorAll('.concept:not(.withheld)')].map((s) => s.textContent.trim()) : [],
                values: Object.fromEntries([...document.querySelectorAll('#info tr[data-feature]')].map((tr) =>
                    [tr.dataset.feature, tr.children[1].textContent])),
            };
        });
        check(`clicking texture ${t.id}'s colour shows texture ${t.id}`, info.texture === t.id, info);
        const expectedWords = (words.get(t.id) || []).map((w) => w.label).sort();
        check('the info panel shows the texture\'s words', JSON.stringify(info.words.slice().sort()) === JSON.stringify(expectedWords),
            { shown: info.words, expected: expectedWords });
        const texel = report.texels.find((x) => x.id === info.texel);
        check('the clicked texel belongs to the texture', texel && texel.texture === t.id, info.texel);
        if (texel) {
            // Shown to 4 significant digits (or in exponent form).
            for (const [f, v] of Object.entries(texel.features)) {
                const shown = Number(info.values[f]);
                check(`texel ${texel.id} ${f} shown`, v === null ? info.values[f] === '—'
                    : Math.abs(shown - v) <= 1e-3 * Math.max(Math.abs(v), 1e-300), { shown: info.values[f], value: v });
            }
        }
    }

    step('click a face');
    // ---- editing: move a bound so that a known word leaves a known texture ---------------
    const dictionary = await p.evaluate(async () => (await fetch('/api/dictionary')).json());
    const conceptsById = new Map(dictionary.concepts.map((c) => [c.id, c]));
    const versionBefore = await p.$eval('#dictionary-info', (e) => e.dataset.version);
    // A chosen word C of a texture T with value v: a new bound that leaves v out of C.
    let move = null;
    for (const t of report.textures) {
        for (const w of words.get(t.id) || []) {
            const c = conceptsById.get(w.concept);
            if (!c || move) continue;
            const v = w.value;
            const step = Math.max(Math.abs(v), 1) * 0.1;
            if (c.upper !== null && c.lower !== null && v > c.lower) move = { side: 'upper', value: (c.lower + v) / 2 };
            else if (c.upper !== null && c.lower === null) move = { side: 'upper', value: v - step };
            else if (c.upper === null && c.lower !== null) move = { side: 'lower', value: v + step };
            if (move) Object.assign(move, { texture: t.id, concept: c, label: w.label, v });
        }
    }
    check('a word whose bound can move', move !== null);
    const result = { object: target };
    if (move) {
        const text = Number(move.value.toPrecision(6)).toString();
        await setInput(p, move.concept.feature, `input[data-bound="${move.concept.id}:${move.side}"]`, text);
        await waitPreview(p, 1);
        const after = await legendWords(p, move.texture);
        check(`after ${move.concept.id} ${move.side} = ${text}, texture ${move.texture} no longer says "${move.label}"`,
            !after.words.includes(move.label), after);
        check(`texture ${move.texture} is highlighted as changed`, after.changed, after);
        result.bound = { concept: move.concept.id, side: move.side, value: text, v: move.v };
    }

    step('move a bound');
    // ---- rename a label: the legend shows the new one ------------------------------------
    const renamed = (() => {
        for (const t of report.textures) for (const w of words.get(t.id) || []) {
            if (!move || w.concept !== move.concept.id) return { texture: t.id, concept: conceptsById.get(w.concept), old: w.label };
        }
        return null;
    })();
    check('a word to rename', renamed !== null);
    if (renamed) {
        const newLabel = `renamed ${renamed.concept.id}`;
        await setInput(p, renamed.concept.feature, `input[data-label="${renamed.concept.id}:en"]`, newLabel);
        await waitPreview(p, result.bound ? 2 : 1);
        const after = await legendWords(p, renamed.texture);
        check(`texture ${renamed.texture} shows the new label "${newLabel}"`, after.words.includes(newLabel) && !after.words.includes(renamed.old), after);
        result.label = { concept: renamed.concept.id, value: newLabel };
    }

    step('rename a label');
    // ---- a bad edit shows its problem with line and column, and is never saved -----------
    // It replaces the bound edit above (same bound), then the good value is typed back.
    if (move) {
        const c = move.concept;
        const editsBefore = await p.$$eval('#edits li', (l) => l.length);
        const bad = 'x' + result.bound.value;
        const selector = `input[data-bound="${c.id}:${move.side}"]`;
        const previous = await p.$eval(selector, (e) => e.value);
        await setInput(p, c.feature, selector, bad);
        await p.waitForFunction(() => document.querySelectorAll('#problems li').length > 0, { timeout: 10000 }).catch(() => {});
        const problems = await p.$$eval('#problems li', (lis) => lis.map((li) => ({ line: Number(li.dataset.line), column: Number(li.dataset.column), text: li.textContent })));
        check('a bound that is not a number shows a problem with its line and column', problems.length > 0 &&
            problems.every((q) => q.line > 0 && q.column > 0) && problems.some((q) => q.line >= c.line), problems);
        // Put the previous value back: the edit list is as before, the problems go away.
        await setInput(p, c.feature, selector, previous);
        await p.waitForFunction(() => document.querySelectorAll('#problems li').length === 0, { timeout: 10000 }).catch(() => {});
        check('fixing the edit clears the problems', (await p.$$eval('#problems li', (l) => l.length)) === 0);
        check('the edit list is back to the good edits', (await p.$$eval('#edits li', (l) => l.length)) === editsBefore);
    }

    step('bad edit');
    // ---- save: the version changes -------------------------------------------------------
    await p.click('#save');
    await p.waitForFunction(() => document.querySelector('#save-status').dataset.version, { timeout: 10000 }).catch(() => {});
    const saved = await p.$eval('#save-status', (e) => e.dataset.version || null);
    check('save answers a version', !!saved, saved);
    check('save changes the version', saved !== versionBefore, { before: versionBefore, saved });
    // The status says "saved" once the page has reloaded the server's words (no re-render left).
    await p.waitForFunction(() => /^saved version/.test(document.querySelector('#status').textContent), { timeout: 10000 }).catch(() => {});
    check('the header shows the saved version', (await p.$eval('#dictionary-info', (e) => e.dataset.version)) === saved);
    check('no pending edit after saving', (await p.$$eval('#edits li', (l) => l.length)) === 0);
    result.version_before = versionBefore;
    result.version = saved;

    step('save');
    // ---- fitting: a mark "texture T is C" for a word T does not carry ---------------------
    // Proposed bounds, once applied, must put T's value of C's feature inside C (the mark
    // reproduced), or the mark comes back unsatisfied with a reason.
    {
        let mark = null;
        for (const t of report.textures) {
            const values = new Map(report.annotation.textures.find((a) => a.texture === t.id).features.map((f) => [f.feature, f.value]));
            for (const c of dictionary.concepts) {
                const v = values.get(c.feature);
                if (mark || v === undefined || v === null || (words.get(t.id) || []).some((w) => w.concept === c.id)) continue;
                if (c.lower !== null && c.upper !== null && (v < c.lower || v >= c.upper)) mark = { texture: t.id, concept: c, v };
            }
        }
        if (mark) {
            await p.click(`#legend li[data-texture="${mark.texture}"] .legend-texture`);
            await p.select(`#legend li[data-texture="${mark.texture}"] select.mark-concept`, mark.concept.id);
            await p.click(`#legend li[data-texture="${mark.texture}"] button.mark-yes`);
            await p.click('#propose');
            await p.waitForSelector('#proposal:not([hidden])', { timeout: 10000 }).catch(() => {});
            const proposal = await p.evaluate(() => ({
                edits: document.querySelectorAll('#fit-edits .fit-edit').length,
                unsatisfied: [...document.querySelectorAll('#unsatisfied li')].map((li) => li.textContent),
            }));
            check('fit proposes bounds or says why not', proposal.edits > 0 || proposal.unsatisfied.length > 0, proposal);
            console.log(`  fit: texture ${mark.texture} is ${mark.concept.id}: ${proposal.edits} edit(s), ${proposal.unsatisfied.length} unsatisfied`);
            if (proposal.edits > 0) {
                await p.click('#apply-fit');
                await waitPreview(p, proposal.edits);
                const bounds = await p.evaluate((id) => ['lower', 'upper'].map((s) => document.querySelector(`input[data-bound="${id}:${s}"]`).value), mark.concept.id);
                const lo = Number(bounds[0]), hi = bounds[1] === '∞' ? Infinity : Number(bounds[1]);
                check(`the fitted ${mark.concept.id} holds texture ${mark.texture}'s value ${mark.v}`,
                    (bounds[0] === '-∞' || lo <= mark.v) && mark.v < hi, bounds);
            }
        }
    }

    step('fit');
    // ---- without --dictionary: the bundled dictionary, previews but no save --------------
    if (readOnlyUrl && move) {
        const r = await browser.newPage();
        r.on('pageerror', (e) => check('no error in the page', false, e.message));
        await r.setViewport({ width: 1280, height: 800 });
        await r.goto(`${readOnlyUrl.replace(/#.*$/, '')}#/objects/${encodeURIComponent(target)}`);
        await r.waitForFunction('window.geotexReady === true', { timeout: 30000 });
        check('read-only: Save is disabled', await r.$eval('#save', (b) => b.disabled));
        await setInput(r, move.concept.feature, `input[data-bound="${move.concept.id}:${move.side}"]`, result.bound.value);
        await waitPreview(r, 1);
        const after = await legendWords(r, move.texture);
        check('read-only: the preview works', !after.words.includes(move.label) && after.changed, after);
        check('read-only: Save stays disabled with an edit', await r.$eval('#save', (b) => b.disabled));
        // Dragging a bound line on a histogram: the first bound drawn inside its histogram's
        // range is dragged 40 pixels right; on release its input shows the value under the
        // pointer and a preview runs with one more edit.
        const dragged = await dragFirstBound(r, 40);
        check('a bound line to drag', dragged !== null);
        if (dragged) {
            await waitPreview(r, 2);
            const shown = Number(await r.$eval(`input[data-bound="${dragged.key}"]`, (e) => e.value));
            check(`dragged ${dragged.key} from ${dragged.from} to about ${dragged.to}`,
                Math.abs(shown - dragged.to) <= dragged.pixel * 1.5 && Math.abs(shown - dragged.from) > dragged.pixel * 20,
                { shown, ...dragged });
        }
        step('read-only server');
    }

    result.open_ms = openMs;
    fs.writeFileSync(resultFile, JSON.stringify(result, null, 2));
} finally {
    await browser.close();
}
console.log(`workbench: ${failures ? failures + ' failure(s)' : 'ok'} in ${((Date.now() - started) / 1000).toFixed(1)} s`);
process.exit(failures ? 1 : 0);

// ---- helpers -----------------------------------------------------------------------------

// Types into an input of the editor as a curator does: opens the feature's section, selects
// the old text, types, and leaves the field (which fires `change`).
async function setInput(page, feature, selector, text) {
    await page.$eval(`#features details[data-feature="${feature}"]`, (d) => { d.open = true; });
    await page.click(selector, { clickCount: 3 });
    await page.keyboard.down('Control');
    await page.keyboard.press('KeyA');
    await page.keyboard.up('Control');
    await page.keyboard.type(text);
    await page.keyboard.press('Tab');
}

// Drags, with the mouse, the first bound line that lies inside its histogram `dx` CSS pixels to
// the right (within the histogram). Returns {key, from, to, pixel} (values; pixel: the value
// of one CSS pixel), or null when no histogram has a bound inside its range.
async function dragFirstBound(page, dx) {
    const found = await page.evaluate((dx) => {
        for (const d of document.querySelectorAll('#features details')) {
            d.open = true;
            const canvas = d.querySelector('canvas[data-histogram]');
            const range = canvas && canvas.range;
            if (!range) continue;
            const r = canvas.getBoundingClientRect();
            const pixel = (range[1] - range[0]) / r.width;
            for (const input of d.querySelectorAll('input[data-bound]')) {
                const v = Number(input.value);
                if (input.disabled || !Number.isFinite(v) || v <= range[0] || v >= range[1]) continue;
                const x = r.left + (v - range[0]) / pixel;
                if (x + dx >= r.right - 2) continue;
                d.scrollIntoView();
                const r2 = canvas.getBoundingClientRect();
                const x2 = r2.left + (v - range[0]) / pixel;
                return { key: input.dataset.bound, from: v, to: v + dx * pixel, pixel, x: x2, y: r2.top + r2.height / 2 };
            }
            d.open = false;
        }
        return null;
    }, dx);
    if (!found) return null;
    await page.mouse.move(found.x, found.y);
    await page.mouse.down();
    await page.mouse.move(found.x + dx / 2, found.y, { steps: 4 });
    await page.mouse.move(found.x + dx, found.y, { steps: 4 });
    await page.mouse.up();
    return { key: found.key, from: found.from, to: found.to, pixel: found.pixel };
}

async function waitPreview(page, numEdits) {
    await page.waitForFunction((n) => document.querySelectorAll('#edits li').length === n &&
        /^preview:/.test(document.querySelector('#status').textContent), { timeout: 15000 }, numEdits)
        .catch(() => check(`a preview with ${numEdits} edit(s)`, false, 'timed out'));
}

async function legendWords(page, texture) {
    return page.$eval(`#legend li[data-texture="${texture}"] .legend-texture`, (d) => ({
        words: [...d.querySelectorAll('.concept:not(.withheld)')].map((s) => s.textContent.trim()),
        changed: d.classList.contains('changed'),
    }));
}
