// How long the workbench takes to put an object on screen (issue 19: a 1.3-million-face object
// within 3 s): opens URL#/objects/OBJECT in headless Chromium RUNS times and prints, per run,
// the page's own timings (window.geotexTimings, milliseconds from the click: mesh transfer,
// GTXM parse, geometry, colours, first frame drawn) as one JSON line.
// SETTLE_MS: how long the list stays on screen before the click (default 0: at once); the
// server makes an object's mesh while the list shows its thumbnail, so a curator who looks at
// the list for a moment opens the object with its mesh made.
// SETTLE_MS `link`: opens URL#/objects/OBJECT in a new page instead, as a link sent to a
// colleague; since_page_start is then the wait from the page's own start.
// Usage: node workbench_open_time.mjs URL OBJECT [RUNS] [SETTLE_MS|link]
import { launchChromium } from './chromium.mjs';

const [url, object, runs = '3', settle = '0'] = process.argv.slice(2);
if (!object) {
    console.error('usage: node workbench_open_time.mjs URL OBJECT [RUNS] [SETTLE_MS]');
    process.exit(1);
}
const browser = await launchChromium();
try {
    for (let i = 0; i < Number(runs); i++) {
        const page = await browser.newPage();
        await page.setViewport({ width: 1280, height: 800 });
        if (settle === 'link') {
            const t0 = Date.now();
            await page.goto(`${url.replace(/#.*$/, '')}#/objects/${encodeURIComponent(object)}`);
            await page.waitForFunction('window.geotexReady === true', { timeout: 120000 });
            const wall = Date.now() - t0;
            const timings = await page.evaluate(() => ({ ...window.geotexTimings }));
            delete timings.start;
            console.log(JSON.stringify({ object, run: i + 1, link: true, wall_ms: wall, ...timings }));
            await page.close();
            continue;
        }
        // From the list, as a curator opens an object: the page and three.js are loaded already.
        await page.goto(`${url.replace(/#.*$/, '')}#/`);
        await page.waitForFunction('window.geotexReady === true', { timeout: 60000 });
        await new Promise((resolve) => setTimeout(resolve, Number(settle)));
        const t0 = Date.now();
        // geotexReady is reset here: the hashchange that resets it comes a moment later.
        await page.evaluate((id) => {
            window.geotexReady = false;
            location.hash = `#/objects/${encodeURIComponent(id)}`;
        }, object);
        await page.waitForFunction('window.geotexReady === true', { timeout: 120000 });
        const wall = Date.now() - t0;
        const timings = await page.evaluate(() => ({ ...window.geotexTimings }));
        delete timings.start;
        console.log(JSON.stringify({ object, run: i + 1, on_screen_ms: wall, ...timings }));
        await page.close();
    }
} finally {
    await browser.close();
}
