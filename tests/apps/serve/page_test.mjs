// needle serve's page in the system's Chromium, driven through the DevTools protocol by
// puppeteer-core (apps/serve/web/package.json): the page loads, the preload slider is moved by
// the mouse (a click on its track, as a hand moves it), and the n_dyn the page then shows equals
// `needle check --json`'s for the case with that preload, saved as the page saves it. The
// screenshot is kept as the test's artefact (serve-page-puppeteer.png in the working folder).
//
//   node tests/apps/serve/page_test.mjs NEEDLE CASE
//
// Exit 0 passed, 1 failed, 77 skipped (no Chromium or puppeteer-core, outside CI).
import { spawn, execFileSync } from "node:child_process";
import { createRequire } from "node:module";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";

const [needle, casePath] = process.argv.slice(2);
const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), "../../..");
const chromium = process.env.CHROMIUM || "/usr/bin/chromium";
const skip = why => {
  if (process.env.CI) { console.error("FAIL: " + why + " on CI (bash scripts/setup.sh --tests)"); process.exit(1); }
  console.error("SKIP: " + why + " (bash scripts/setup.sh --tests)");
  process.exit(77);
};
let puppeteer;
try {
  puppeteer = createRequire(path.join(root, "apps/serve/web/package.json"))("puppeteer-core");
} catch (e) {
  skip("puppeteer-core is not installed in apps/serve/web");
}
if (!fs.existsSync(chromium)) skip("chromium is not installed");

const fail = why => { console.error("FAIL: " + why); process.exitCode = 1; };

const server = spawn(needle, ["serve", casePath, "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
const url = await new Promise((resolve, reject) => {
  let out = "";
  server.stdout.on("data", d => {
    out += d;
    const m = /at (http:\/\/[^ ]+\/) /.exec(out);
    if (m) resolve(m[1]);
  });
  server.on("exit", code => reject(new Error("needle serve ended with " + code + ": " + out)));
  setTimeout(() => reject(new Error("needle serve did not start: " + out)), 30000);
});

const browser = await puppeteer.launch({
  executablePath: chromium, headless: true,
  args: ["--no-sandbox", "--disable-gpu", "--window-size=1400,1000"],
  defaultViewport: { width: 1400, height: 1000 },
});
try {
  const page = await browser.newPage();
  const done = () => page.evaluate(() => Number(document.body.dataset.done || 0));
  await page.goto(url);
  await page.waitForFunction(() => Number(document.body.dataset.done || 0) > 0, { timeout: 60000 });
  const before = await page.$eval("#n_dyn", e => e.textContent);
  const first = await done();
  // The preload slider, moved by the mouse: a click at a third of its track.
  const slider = await page.$('input[type=range][id="spring.preload_kgf"]');
  if (!slider) throw new Error("the page has no preload slider");
  const box = await slider.boundingBox();
  await page.mouse.click(box.x + box.width / 3, box.y + box.height / 2);
  await page.waitForFunction(n => Number(document.body.dataset.done || 0) > n, { timeout: 60000 },
                             first);
  const value = Number(await slider.evaluate(e => e.value));
  const shown = await page.$eval("#n_dyn", e => e.textContent);
  await page.screenshot({ path: "serve-page-puppeteer.png" });
  // The command line on the same design: the case as the page saves it.
  const saved = await (await fetch(url + "api/case-text", {
    method: "POST", body: JSON.stringify({ spring: { preload_kgf: value } }) })).json();
  const tmp = fs.mkdtempSync(path.join(os.tmpdir(), "needle-page-"));
  const file = path.join(tmp, "design.toml");
  fs.writeFileSync(file, saved.toml);
  let out;
  try {
    out = execFileSync(needle, ["check", file, "--json", "--out", tmp], { encoding: "utf8" });
  } catch (e) {
    out = e.stdout;  // exit 1: the check fails, its JSON is still the answer
  }
  const nDyn = JSON.parse(out).overspeed.liftoff_rpm_dynamic;
  const expected = nDyn === null ? "–" : Number(nDyn).toFixed(1);
  console.log(`preload ${value} kgf: the page shows n_dyn ${shown}, needle check ${expected} ` +
              `(before the move: ${before})`);
  if (shown !== expected) fail(`the page shows n_dyn ${shown}, needle check --json ${expected}`);
  if (shown === before) fail("the slider's move did not change n_dyn (" + before + ")");
  if (!(fs.statSync("serve-page-puppeteer.png").size > 10000)) fail("the screenshot is empty");
  const charts = await page.$$eval(".uplot", els => els.length);
  if (charts < 4) fail(`uPlot drew ${charts} charts, expected at least 4`);
} catch (e) {
  fail(e.message);
} finally {
  await browser.close();
  server.kill("SIGINT");
  const code = await new Promise(resolve => server.on("exit", resolve));
  if (code !== 0) fail("needle serve ended with " + code + " on SIGINT");
}
