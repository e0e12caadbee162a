// Drives an exported web page in a real browser for tests/webpage.rs: Debian's Chromium,
// headless, through playwright-core (both installed by .ci/run), the page opened from file://
// with the network off. Takes the steps of a plan, screenshots at 1280×800, and prints one JSON
// report on stdout; the Rust test judges it.
//
//   node browser.js PAGE.html OUT_DIR PLAN_JSON
//
// PLAN: {"steps": [{"shot": "name"} | {"hide": i} | {"show": i} | {"variant": k} |
//                  {"removed": opacity} | {"view": k} | {"pick": [x, y]}]}
// Every step after the first waits for the page's next frame. The report:
// {"errors": [...], "requests": [...], "state": {...}, "overlays": [[x, y, w, h], ...],
//  "steps": [{"shot": "OUT_DIR/name.png", "state": {...}} | {"pick": …}, ...]}.
// `errors` holds every console error and warning (but Chromium's note that a screenshot read the
// canvas back), uncaught exception and failed request.

'use strict';

const path = require('path');
const { pathToFileURL } = require('url');

const packageDir = process.env.CUTAWAY_PLAYWRIGHT;
if (!packageDir) {
  console.error('CUTAWAY_PLAYWRIGHT is not set (the playwright-core package folder)');
  process.exit(2);
}
const { chromium } = require(packageDir);

const [pagePath, outDir, planText] = process.argv.slice(2);
const plan = JSON.parse(planText);

const FLAGS = [
  '--no-sandbox',
  '--headless=new',
  '--disable-gpu',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--disable-quic',
  '--no-first-run',
  '--disable-features=Translate,MediaRouter,OptimizationHints',
];

async function main() {
  const browser = await chromium.launch({
    executablePath: process.env.CUTAWAY_CHROMIUM || '/usr/bin/chromium',
    args: FLAGS,
  });
  const errors = [];
  const requests = [];
  try {
    const context = await browser.newContext({
      viewport: { width: 1280, height: 800 },
      deviceScaleFactor: 1,
      offline: true,
    });
    // Nothing but the file itself and what it makes in memory may be loaded.
    await context.route('**/*', (route) => {
      const url = route.request().url();
      if (/^(file|blob|data):/.test(url)) return route.continue();
      requests.push(url);
      return route.abort();
    });
    const page = await context.newPage();
    page.on('console', (message) => {
      // Chromium's own note that a screenshot read the WebGL canvas back is not the page's.
      const readBack = /GL Driver Message .*Performance.*GPU stall due to ReadPixels/.test(message.text());
      if (message.type() === 'error' || (message.type() === 'warning' && !readBack)) {
        errors.push(`console ${message.type()}: ${message.text()}`);
      }
    });
    page.on('pageerror', (error) => errors.push(`uncaught: ${error.message}`));
    page.on('requestfailed', (request) => errors.push(`request failed: ${request.url()}`));
    page.on('request', (request) => {
      if (!/^(file|blob|data):/.test(request.url())) requests.push(request.url());
    });

    const started = Date.now();
    await page.goto(pathToFileURL(path.resolve(pagePath)).href);
    await waitReady(page, null);
    const loadMs = Date.now() - started;
    const overlays = await page.evaluate(() =>
      Array.from(document.querySelectorAll('.overlay'))
        .map((e) => e.getBoundingClientRect())
        .filter((r) => r.width > 0 && r.height > 0)
        .map((r) => [r.x, r.y, r.width, r.height]),
    );
    const steps = [];
    for (const step of plan.steps) {
      if (step.shot !== undefined) {
        await page.evaluate(() => window.cutaway.nextFrame());
        const file = path.join(outDir, `${step.shot}.png`);
        await page.screenshot({ path: file });
        steps.push({ shot: file, state: await state(page) });
      } else if (step.hide !== undefined || step.show !== undefined) {
        const i = step.hide ?? step.show;
        const box = page.locator(`input[type=checkbox][data-structure="${i}"]`);
        await box.scrollIntoViewIfNeeded();
        await box.click();
        await page.evaluate(() => window.cutaway.nextFrame());
        steps.push({ toggled: i, state: await state(page) });
      } else if (step.variant !== undefined) {
        await page.selectOption('#cutaway-variant', String(step.variant));
        await waitReady(page, step.variant);
        steps.push({ variant: step.variant, state: await state(page) });
      } else if (step.removed !== undefined) {
        await page.locator('#cutaway-removed').fill(String(step.removed));
        await page.evaluate(() => window.cutaway.nextFrame());
        steps.push({ removed: step.removed, state: await state(page) });
      } else if (step.view !== undefined) {
        await page.locator(`button[data-view="${step.view}"]`).click();
        await page.waitForTimeout(600);
        await page.evaluate(() => window.cutaway.nextFrame());
        steps.push({ view: step.view, state: await state(page) });
      } else if (step.pick !== undefined) {
        const [x, y] = step.pick;
        steps.push({ pick: await page.evaluate(([x, y]) => window.cutaway.pick(x, y), [x, y]) });
      }
    }
    const report = { errors, requests, loadMs, state: await state(page), overlays, steps };
    process.stdout.write(JSON.stringify(report) + '\n');
  } finally {
    await browser.close();
  }
}

async function waitReady(page, variant) {
  await page.waitForFunction(
    (variant) =>
      document.body.dataset.state === 'failed' ||
      (document.body.dataset.state === 'ready' &&
        (variant === null || document.body.dataset.variant === String(variant))),
    variant,
    { timeout: 180000, polling: 100 },
  );
  const failed = await page.evaluate(() => document.body.dataset.state === 'failed');
  if (failed) {
    const text = await page.evaluate(() => document.getElementById('cutaway-status').textContent);
    throw new Error(`the page failed: ${text}`);
  }
}

function state(page) {
  return page.evaluate(() => window.cutaway.state());
}

main().catch((error) => {
  console.error(String(error && error.stack ? error.stack : error));
  process.exit(1);
});
