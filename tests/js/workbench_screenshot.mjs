// The README's picture of the workbench: one object of a batch open at 1280x800, a face of
// its first texture clicked, one feature's histogram open. Run by scripts/workbench_screenshot.sh.
// Usage: node workbench_screenshot.mjs URL OBJECT FEATURE OUT.png
import { launchChromium } from './chromium.mjs';

const [url, object, feature, out] = process.argv.slice(2);
if (!out) {
    console.error('usage: node workbench_screenshot.mjs URL OBJECT FEATURE OUT.png');
    process.exit(1);
}
const browser = await launchChromium();
try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1280, height: 800 });
    await page.goto(`${url.replace(/#.*$/, '')}#/objects/${encodeURIComponent(object)}`);
    await page.waitForFunction('window.geotexReady === true', { timeout: 60000 });
    // Click the face nearest the centre that belongs to a texel, found with the page's picker.
    const box = await (await page.$('#viewport canvas')).boundingBox();
    const at = await page.evaluate((w, h) => {
        for (let r = 0; r < Math.min(w, h) / 2; r += 4) {
            for (let a = 0; a < 360; a += 10) {
                const x = w / 2 + r * Math.cos((a * Math.PI) / 180), y = h / 2 + r * Math.sin((a * Math.PI) / 180);
                const hit = window.geotexPick(x, y);
                if (hit && hit.texel >= 0) return { x, y };
            }
        }
        return null;
    }, box.width, box.height);
    if (at) await page.mouse.click(box.x + at.x, box.y + at.y);
    await page.$eval(`#features details[data-feature="${feature}"]`, (d) => { d.open = true; });
    await page.$eval('#fit', (d) => { d.open = false; });
    await new Promise((r) => setTimeout(r, 500));
    await page.screenshot({ path: out });
} finally {
    await browser.close();
}
