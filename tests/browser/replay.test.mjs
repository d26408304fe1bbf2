// The demo's --animate pages in a real browser: Debian's Chromium, headless, driven by playwright-core (which
// downloads no browser of its own). For every scenario the demo lists that has particles, and for two harder cases
// (a 32 x 32 cloth and a cloth that diverges), the test writes the page with the built demo and checks that:
//   - it runs without a script error or a console error, and asks for nothing but its own file;
//   - it decodes its recording (window.replay.ready, no window.replay.error);
//   - the picture changes between two times (pixels of the canvas);
//   - the time slider seeks: the time shown follows it, and the same time gives the same picture;
//   - play advances the time and pause stops it;
//   - dragging on the picture orbits the camera (the picture changes, the time does not);
//   - it holds what the scenario has (window.replay.scene against the list below: colliders by kind, radii, pins,
//     anchors, springs, rods, surface);
//   - where there are colliders, they are drawn (hiding them changes the picture, showing them again restores it),
//     a still one stays put and a moving one moves (with everything else hidden, two times give the same picture,
//     or not);
//   - a run with --profile shows each stage's time per step for the frame on screen (a stacked bar and a line that
//     follow the slider), and a run without shows no such line.
// A last page, the cloth's with radii, rods, cables, anchors and one collider of each kind (the box moving) written
// into its scene, checks the drawing of what no scenario has all of; and the pages of three sample scenes (the
// scene command), the playground among them with every object and collider kind of the scene format, loads too.
// Every page must start playing when it opens.
// Run: npm ci && node --test replay.test.mjs (the demo built in Release first: dotnet build -c Release).
// DEMO_DLL overrides the demo's path, CHROMIUM the browser's, REPLAY_SCREENSHOTS names a folder for a PNG per page.
import { after, before, describe, it } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { chromium } from "playwright-core";

const here = dirname(fileURLToPath(import.meta.url));
const demo = process.env.DEMO_DLL || resolve(here, "../../samples/ParticlePhysics.Demo/bin/Release/net10.0/ParticlePhysics.Demo.dll");
const executablePath = process.env.CHROMIUM || "/usr/bin/chromium";
const screenshots = process.env.REPLAY_SCREENSHOTS || null;
const work = mkdtempSync(join(tmpdir(), "pp-replay-"));

function runDemo(args) {
  try {
    execFileSync("dotnet", [demo, ...args, "--format", "csv"], { stdio: ["ignore", "ignore", "pipe"], timeout: 300_000 });
    return { status: 0, stderr: "" };
  } catch (error) {
    if (typeof error.status !== "number") throw error;
    return { status: error.status, stderr: String(error.stderr) };
  }
}

// The demo's own list of commands (its --help), less convergence: every scenario gets its page tested.
function scenarios() {
  const help = execFileSync("dotnet", [demo, "--help"], { encoding: "utf8" });
  const commands = help.slice(help.indexOf("Commands:")).split("\n").slice(1)
    .map((line) => /^\s{2}([a-z][a-z0-9-]*)\s/.exec(line)).filter(Boolean).map((m) => m[1]);
  return commands.filter((name) => name !== "convergence" && name !== "scene");
}

// What each scenario's page must hold (a subset of window.replay.scene), from the contract's description of it.
const expected = {
  "free-fall": { colliders: [], largestRadius: 0, pinned: 0, anchors: 0, springs: 0, rods: 0 },
  "mass-spring-damper": { colliders: [], anchors: 1, springs: 1, rods: 0 },
  "two-mass-chain": { colliders: [], anchors: 1, springs: 2, rods: 0 },
  "cloth": { colliders: [], pinned: 2, rods: 0, triangles: 2 * 10 * 10 },
  "pendulum": { colliders: [], anchors: 1, rods: 1, springs: 0 },
  "hanging-chain": { colliders: [], pinned: 2, rods: 10, springs: 0 },
  "bouncing-ball": { colliders: ["plane"], largestRadius: 0, pinned: 0 },
  "collision": { colliders: [], largestRadius: 0.1, pinned: 0 },
  "drape": { colliders: ["sphere"], largestRadius: 0.01, pinned: 0, triangles: 2 * 10 * 10 },
};

// Sample scenes, run by the scene command: the playground holds every object and collider kind of the scene format.
const scenes = resolve(here, "../../samples/scenes");
const sceneCases = {
  "scene-playground": { file: "playground.json", scene: { colliders: ["plane", "sphere", "capsule", "box (moving)"], pinned: 3, springs: 1, rods: 2, cables: 1, loads: 1, largestRadius: 0.1 } },
  "scene-newtons-cradle": { file: "newtons-cradle.json", scene: { colliders: [], pinned: 5, rods: 5, largestRadius: 0.05 } },
  "scene-rope-bridge": { file: "rope-bridge.json", scene: { colliders: [], pinned: 4, cables: 40, rods: 19, springs: 40, loads: 2 } },
};

// Each case's page is written up front, so that a scenario the demo refuses (a plain ODE) gets its own one test.
if (!existsSync(demo)) throw new Error(`the demo is not built at ${demo}: run dotnet build -c Release first`);
const cases = scenarios().map((name) => ({ name, args: [name], exit: 0, scene: expected[name] }));
cases.push({ name: "cloth-32x32", args: ["cloth", "--resolution", "1/31", "--duration", "2"], exit: 0 });
cases.push({ name: "cloth-diverged", args: ["cloth", "--dt", "0.0166667"], exit: 3 });
cases.push({ name: "pendulum-profiled", args: ["pendulum", "--duration", "2", "--profile"], exit: 0, profile: true });
cases.push({ name: "scene-playground-profiled", args: ["scene", join(scenes, "playground.json"), "--duration", "2", "--profile"], exit: 0, profile: true });
for (const [name, c] of Object.entries(sceneCases)) cases.push({ name, args: ["scene", join(scenes, c.file)], exit: 0, scene: c.scene });
for (const c of cases) {
  c.file = join(work, c.name + ".html");
  c.run = runDemo([...c.args, "--animate", c.file]);
  c.plain = c.run.status === 2 && /--animate replays particles, and .* is a plain ODE/.test(c.run.stderr);
}

// Every kind of shape the page can draw, before any scenario has them all: the cloth's page with radii, rods,
// cables (one slack), anchors and the four colliders written into its scene.
const shapes = {
  name: "cloth-with-every-shape", file: join(work, "cloth-with-every-shape.html"), exit: 0, plain: false, run: { status: 0, stderr: "" },
  scene: { colliders: ["plane", "sphere", "capsule", "box (moving)"], largestRadius: 0.035, rods: 3, cables: 2, anchors: 1 },
};
{
  const html = readFileSync(cases.find((c) => c.name === "cloth").file, "utf8");
  const marker = /(<script type="application\/json" id="replay-data">)(.*?)(<\/script>)/s;
  const data = JSON.parse(marker.exec(html)[2]);
  data.radii = Array.from({ length: data.particles }, (_, i) => (i % 11 === 10 ? 0.035 : 0.012));
  data.links.rod = [0, 1, 1, 2, 2, 3];
  data.links.cable = [110, 120, 60, 121];
  data.links.cableLengths = [5, 0.01];
  data.anchors.push([0.5, 0.3, 0.5]);
  const unit = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  const c = Math.cos(0.5), s = Math.sin(0.5);
  data.colliders = [
    { kind: "plane", center: [0, -1.3, 0], radius: 0, halfExtents: [0, 0, 0], axes: unit },
    { kind: "sphere", center: [0.5, -0.75, 0.6], radius: 0.22, halfExtents: [0, 0, 0], axes: unit },
    { kind: "capsule", center: [1.3, -0.6, 0.2], radius: 0.08, halfExtents: [0, 0.3, 0], axes: [[0, 0, -1], [1, 0, 0], [0, -1, 0]] },
    { kind: "box", center: [-0.35, -1.0, 0.5], radius: 0, halfExtents: [0.15, 0.25, 0.1], axes: [[c, 0, -s], [0, 1, 0], [s, 0, c]], velocity: [0.1, 0, 0] },
  ];
  writeFileSync(shapes.file, html.replace(marker, (_, open, __, close) => open + JSON.stringify(data).replace(/</g, "\\u003c") + close));
  cases.push(shapes);
}

let browser;
before(async () => {
  browser = await chromium.launch({
    executablePath,
    args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking",
      "--disable-component-update", "--disable-sync"],
  });
});
after(async () => {
  await browser?.close();
  rmSync(work, { recursive: true, force: true });
});

for (const c of cases.filter((c) => c.plain)) {
  it(`${c.name}: has no particles, and the demo refuses --animate with one error line and no page`, () => {
    assert.equal(c.run.stderr.trim().split("\n").length, 1);
    assert.equal(existsSync(c.file), false);
  });
}

for (const c of cases.filter((c) => !c.plain)) {
  describe(c.name, { timeout: 240_000 }, () => {
    const file = c.file, exit = c.run.status;
    let page, problems = [], requests = [], playingAtOpen = null, timeAtOpen = null;

    before(async () => {
      assert.ok(existsSync(file), `the demo (exit ${exit}) wrote no page: ${c.run.stderr}`);
      const context = await browser.newContext({ viewport: { width: 1000, height: 680 } });
      page = await context.newPage();
      page.on("pageerror", (error) => problems.push("page error: " + error.message));
      page.on("console", (message) => { if (message.type() === "error") problems.push("console error: " + message.text()); });
      const own = pathToFileURL(file).href;
      await context.route("**/*", (route) => {
        const url = route.request().url();
        if (url === own) return route.continue();
        requests.push(url);
        return route.abort();
      });
      await page.goto(own);
      await page.waitForFunction(() => window.replay && (window.replay.ready || window.replay.error), null, { timeout: 60_000 });
      // A replay plays when it opens; pause it (as a user would, with the button) for the checks that seek.
      playingAtOpen = await page.evaluate(() => window.replay.playedOnOpen);
      timeAtOpen = await page.evaluate(() => new Promise((done) => setTimeout(() => done(window.replay.time), 400)));
      if (await page.evaluate(() => window.replay.playing)) await page.locator("#play").click();
    });
    after(async () => { await page?.context().close(); });

    const rendersNow = () => page.evaluate(() => window.replay.renders);
    // Waits for a render after an action, then for the page to go idle: a render that was already due when the action
    // began (the double-click that resets the view, say) can be the first one counted, and the picture kept then
    // would miss the action (seen: a bounce kept at the time before the seek).
    const settled = async (before) => {
      await page.waitForFunction((n) => window.replay.renders > n, before, { timeout: 30_000 });
      await page.evaluate(() => new Promise((done) => {
        let seen = window.replay.renders, frames = 0;
        const check = () => requestAnimationFrame(() => requestAnimationFrame(() => {
          if (window.replay.renders === seen || ++frames > 120) done(); else { seen = window.replay.renders; check(); }
        }));
        check();
      }));
    };
    // Moves the slider as a user does: types a time (three decimals, as a range input keeps them), or presses End.
    const seekWithSlider = async (t) => {
      const before = await rendersNow();
      const slider = page.locator("#slider");
      if (t === "end") await slider.press("End"); else await slider.fill(String(Number(t.toFixed(3))));
      await settled(before);
    };
    // Keeps the canvas's pixels under a name, and counts the pixels that differ between two kept pictures.
    const keep = (name) => page.evaluate((name) => {
      const canvas = document.getElementById("view");
      (window.kept ??= {})[name] = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height).data;
    }, name);
    const differing = (a, b) => page.evaluate(([a, b]) => {
      const x = window.kept[a], y = window.kept[b];
      if (x.length !== y.length) return Infinity;
      let count = 0;
      for (let i = 0; i < x.length; i += 4) if (x[i] !== y[i] || x[i + 1] !== y[i + 1] || x[i + 2] !== y[i + 2]) count++;
      return count;
    }, [a, b]);

    it("runs without script errors and loads nothing else", () => {
      assert.equal(exit, c.exit, "the demo's exit code");
      assert.deepEqual(problems, []);
      assert.deepEqual(requests, [], "requests beyond the page itself");
      return page.evaluate(() => window.replay).then((replay) => {
        assert.equal(replay.error, null);
        assert.equal(replay.ready, true);
        assert.ok(replay.frameCount >= 2, `${replay.frameCount} frames`);
        assert.ok(replay.duration > 0);
      });
    });

    it("starts playing when it opens", () => {
      assert.equal(playingAtOpen, true, "window.replay.playing when it had loaded");
      assert.ok(timeAtOpen > 0, `the time had not moved 0.4 s after it opened: ${timeAtOpen}`);
    });

    it("changes its picture between two times", async () => {
      const duration = await page.evaluate(() => window.replay.duration);
      await seekWithSlider(0);
      await keep("start");
      await seekWithSlider(duration / 2);
      await keep("middle");
      const changed = await differing("start", "middle");
      assert.ok(changed >= 20, `${changed} pixels changed between t = 0 and t = ${(duration / 2).toFixed(3)}`);
      if (screenshots) { mkdirSync(screenshots, { recursive: true }); await page.screenshot({ path: join(screenshots, c.name + ".png") }); }
    });

    it("seeks with the time slider", async () => {
      const duration = await page.evaluate(() => window.replay.duration);
      const target = Number((0.3 * duration).toFixed(3));
      await seekWithSlider(target);
      assert.ok(Math.abs(await page.evaluate(() => window.replay.time) - target) < 1e-9);
      const shown = await page.locator("#time").textContent();
      assert.match(shown, new RegExp("^t = " + target.toFixed(duration < 10 ? 3 : 2).replace(".", "\\.") + " s / "));
      await keep("seek-a");
      await seekWithSlider("end");
      assert.equal(await page.evaluate(() => window.replay.time), duration, "End on the slider goes to the end");
      await keep("seek-end");
      await seekWithSlider(target);
      await keep("seek-b");
      assert.equal(await differing("seek-a", "seek-b"), 0, "the same time twice gives the same picture");
      assert.ok(await differing("seek-a", "seek-end") > 0, "another time gives another picture");
    });

    it("plays and pauses", async () => {
      await seekWithSlider(0);
      await page.locator("#speed").selectOption("0.1");   // the shortest run (0.28 s) then plays for 2.8 s
      await page.locator("#play").click();
      assert.equal(await page.evaluate(() => window.replay.playing), true);
      await page.waitForFunction(() => window.replay.time > 0, null, { timeout: 30_000 });
      await page.locator("#play").click();
      assert.equal(await page.evaluate(() => window.replay.playing), false);
      const paused = await page.evaluate(() => window.replay.time);
      await page.waitForTimeout(300);
      assert.equal(await page.evaluate(() => window.replay.time), paused);
      assert.equal(await page.locator("#play").textContent(), "Play");
      await page.locator("#speed").selectOption("1");
    });

    it("orbits the camera when the picture is dragged", async () => {
      await seekWithSlider(await page.evaluate(() => window.replay.duration / 3));
      await keep("before-orbit");
      const time = await page.evaluate(() => window.replay.time);
      const box = await page.locator("#view").boundingBox();
      const before = await rendersNow();
      await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
      await page.mouse.down();
      await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 30, { steps: 6 });
      await page.mouse.up();
      await settled(before);
      await keep("after-orbit");
      assert.ok(await differing("before-orbit", "after-orbit") >= 20, "the view turned");
      assert.equal(await page.evaluate(() => window.replay.time), time, "orbiting leaves the time alone");
      assert.deepEqual(problems, []);
      const beforeReset = await rendersNow();
      await page.dblclick("#view");   // back to the home view for the checks that follow
      await settled(beforeReset);
    });

    it(c.profile ? "shows each stage's time per step at the frame on screen" : "shows no stage times without --profile", async () => {
      const line = page.locator("#profile");
      if (!c.profile) {
        assert.equal(await line.isVisible(), false);
        assert.equal(await page.evaluate(() => window.replay.stageTimes(0)), null);
        return;
      }
      assert.equal(await line.isVisible(), true);
      const us = String.raw`[0-9]+(\.[0-9]+)? us`;
      const pattern = new RegExp(`^step ${us}: integration ${us}, forces ${us}, constraints ${us}, contacts ${us}$`);
      const duration = await page.evaluate(() => window.replay.duration);
      const shown = [];
      for (const t of [0, duration / 3, duration]) {
        await seekWithSlider(t);
        const text = await page.evaluate(() => window.replay.profileText);
        assert.match(text, pattern);
        assert.ok((await line.textContent()).includes(text), "the line shows the text");
        // The line is the frame's own times (or the next frame's, for the first, which no step led to), and its total
        // is their sum.
        const { frame, times, data } = await page.evaluate(() => {
          const data = JSON.parse(document.getElementById("replay-data").textContent).profile.seconds;
          return { frame: window.replay.profileFrame, times: window.replay.profileTimes, data };
        });
        assert.deepEqual(times, data.slice(4 * frame, 4 * frame + 4));
        assert.ok(times.every((s) => s >= 0) && times.some((s) => s > 0), `stage times ${times}`);
        const numbers = [...text.matchAll(/([0-9.]+) us/g)].map((m) => Number(m[1]));
        const sum = numbers.slice(1).reduce((a, b) => a + b, 0);
        assert.ok(Math.abs(sum - numbers[0]) <= 0.02 * numbers[0] + 0.2, `the stages ${numbers.slice(1)} add up to the step ${numbers[0]}`);
        shown.push(text);
        const bars = await page.locator("#profile .bar span").count();
        assert.equal(bars, 4, "a bar segment per stage");
      }
      assert.ok(new Set(shown).size >= 2, "other frames show other times: " + shown.join(" | "));
    });

    if (c.scene) {
      it("holds what the scenario has", async () => {
        const scene = await page.evaluate(() => window.replay.scene);
        for (const [key, value] of Object.entries(c.scene)) assert.deepEqual(scene[key], value, key);
      });
    }

    if (c.scene?.colliders?.length) {
      // Shows or hides a part of the picture with its checkbox, as a user does, and waits for the picture.
      const toggle = async (id, on) => {
        const box = page.locator("#" + id);
        if ((await box.isChecked()) === on) return;
        const before = await rendersNow();
        await box.setChecked(on);
        await settled(before);
      };

      it("draws its colliders, a still one in place and a moving one moving", async () => {
        const duration = await page.evaluate(() => window.replay.duration);
        await seekWithSlider(duration / 4);
        await keep("with-colliders");
        await toggle("show-colliders", false);
        await keep("without-colliders");
        const drawn = await differing("with-colliders", "without-colliders");
        assert.ok(drawn >= 200, `${drawn} pixels are the colliders'`);
        await toggle("show-colliders", true);
        await keep("with-colliders-again");
        assert.equal(await differing("with-colliders", "with-colliders-again"), 0, "showing them again restores the picture");

        // Only the colliders (and what never moves: pins, anchors, the floor), at two times.
        for (const id of ["show-surface", "show-links", "show-particles", "show-trails"]) if (await page.locator("#" + id).isVisible()) await toggle(id, false);
        await keep("colliders-early");
        await seekWithSlider(duration);
        await keep("colliders-late");
        const moved = await differing("colliders-early", "colliders-late");
        if (c.scene.colliders.some((k) => k.endsWith("(moving)"))) assert.ok(moved >= 20, `a moving collider moved: ${moved} pixels`);
        else assert.equal(moved, 0, "still colliders stay where they are");
        for (const id of ["show-surface", "show-links", "show-particles", "show-trails"]) if (await page.locator("#" + id).isVisible()) await toggle(id, true);
        assert.deepEqual(problems, []);
      });
    }
  });
}
