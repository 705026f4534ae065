// Debian's Chromium, headless, for the workbench's scripts (workbench.mjs, the screenshot and
// the open-time benchmark): one place for the flags that make WebGL work without a GPU.
// --use-angle=swiftshader --enable-unsafe-swiftshader: WebGL through SwiftShader, on the CPU;
// --no-sandbox: CI runs as root; --disable-dev-shm-usage: containers have a small /dev/shm.
import puppeteer from 'puppeteer-core';

export function launchChromium() {
    return puppeteer.launch({
        executablePath: '/usr/bin/chromium',
        args: ['--headless=new', '--no-sandbox', '--disable-dev-shm-usage', '--use-angle=swiftshader',
            '--enable-unsafe-swiftshader'],
    });
}
