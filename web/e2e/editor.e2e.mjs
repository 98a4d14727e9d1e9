// End-to-end test of the block editor: Playwright (playwright-core) driving Debian's
// chromium against a running `homesim serve`.
//
//   node e2e/editor.e2e.mjs --url http://127.0.0.1:8000/ [--screenshot ../docs/editor.png]
//
// It builds "watch TV" from blocks with the mouse (drag from the toolbox, pick objects in
// the dropdowns), runs it and expects every step to pass; adds a failing step and expects
// its reason on the block; saves and loads files; pastes a program and expects blocks;
// switches homes; asks for key frames and plays the video of the whole program; numbers
// error lines as the user's text does, keeps bubbles inside the pane and drops results of
// an earlier program when a check fails;
// turns a README-style program (`<tv> (1)`, objects not bound to nodes) into action blocks.
// Exits non-zero with a one-line reason on the first failure.
import { chromium } from "playwright-core";
import { parseArgs } from "node:util";
import { readFile } from "node:fs/promises";
import { fileURLToPath } from "node:url";

const { values: opts } = parseArgs({
  options: {
    url: { type: "string", default: "http://127.0.0.1:8000/" },
    screenshot: { type: "string" },
    chromium: { type: "string", default: "/usr/bin/chromium" },
    shots: { type: "string" }, // a folder for extra screenshots
  },
});

let step = "0. Start the browser"; // the step under way, named when one fails
const TV = "tv 410 · livingroom";
const SOFA = "sofa 352 · livingroom";
const WATCH_TV = [
  ["Movement", "WALK", [TV]],
  ["Devices", "SWITCHON", [TV]],
  ["Movement", "WALK", [SOFA]],
  ["Body", "SIT", [SOFA]],
  ["Attention", "WATCH", [TV]],
];
const EXPECTED_TEXT = `Watch TV
Walk to the TV and switch it on, then sit on the sofa and watch TV.

[Walk] <tv> (1.410)
[SwitchOn] <tv> (1.410)
[Walk] <sofa> (1.352)
[Sit] <sofa> (1.352)
[Watch] <tv> (1.410)
`;
const EXAMPLE = fileURLToPath(
  new URL("../../src/homesim/examples/watch_tv.txt", import.meta.url));
const GRAB_REASON = "tv 410 cannot be grabbed (not GRABBABLE)";
const AFFORDANCE_HINT = "this object cannot do that; choose another";
// Title, no description: the typo is on line 4 of this text (line 5 of the 3-line-header
// text the editor sends).
const TYPO = "Watch TV\n\n[Walk] <tv> (1.410)\n[Wlak] <tv> (1.410)\n";
const TYPO_MESSAGE = "line 4: '[Wlak] <tv> (1.410)': unknown action 'Wlak' (did you mean Walk?)";
const README = "[Walk] <tv> (1)\n[SwitchOn] <tv> (1)\n[Walk] <sofa> (1)\n[Sit] <sofa> (1)\n"
  + "[Watch] <tv> (1)\n";

function check(condition, message) {
  if (!condition) throw new Error(message);
}

/** The last block of the (single) stack on the workspace, or null when it is empty. */
async function stackInfo(page) {
  return page.evaluate(() => {
    const ws = window.homesimEditor.workspace();
    const tops = ws.getTopBlocks(true);
    let last = tops[0] ?? null;
    while (last?.getNextBlock()) last = last.getNextBlock();
    const r = last?.getSvgRoot().getBoundingClientRect();
    return {
      stacks: tops.length,
      blocks: ws.getAllBlocks(false).length,
      last: last ? { id: last.id, left: r.left, top: r.top, bottom: r.top + last.height * ws.scale } : null,
    };
  });
}

async function flyoutBlockRect(page, type) {
  return page.evaluate((type) => {
    const flyout = window.homesimEditor.workspace().getToolbox().getFlyout();
    const block = flyout.getWorkspace().getTopBlocks(false).find((b) => b.type === type);
    if (!block) return null;
    const r = block.getSvgRoot().getBoundingClientRect();
    return { left: r.left, top: r.top, height: r.height };
  }, type);
}

/** Drag block `type` from category `category` to the bottom of the stack (or a free spot). */
async function dragBlock(page, category, type) {
  const label = page.locator(".blocklyToolboxCategoryLabel", { hasText: new RegExp(`^${category}$`) });
  await page.locator(".blocklyToolboxCategory", { has: label }).click();
  await page.waitForFunction(() => window.homesimEditor.workspace().getToolbox()
    .getFlyout().isVisible());
  const from = await flyoutBlockRect(page, `hs_${type}`);
  check(from, `no ${type} block in the ${category} flyout`);
  const grab = { x: from.left + 8, y: from.top + 10 };
  const before = await stackInfo(page);
  const area = await page.locator("#blockly").boundingBox();
  const to = before.last
    ? { x: before.last.left + 8, y: before.last.bottom + 10 }
    : { x: area.x + area.width * 0.3, y: area.y + 60 };
  await page.mouse.move(grab.x, grab.y);
  await page.mouse.down();
  await page.mouse.move(grab.x + 20, grab.y + 5, { steps: 4 });
  await page.mouse.move(to.x, to.y, { steps: 15 });
  await page.mouse.up();
  await page.waitForFunction(() => !window.homesimEditor.workspace().isDragging());
  const after = await stackInfo(page);
  check(after.blocks === before.blocks + 1, `dragging ${type} did not add a block`);
  check(after.stacks === 1, `${type} did not snap under the previous block (${after.stacks} stacks)`);
  return after.last.id;
}

/** Open dropdown `field` of block `id` and click the option labelled `label`. */
async function pickOption(page, id, field, label) {
  // Where the field is now: the workspace may scroll a little after a drop, as its content
  // bounds change, so ask again until two readings agree.
  const fieldBox = () => page.evaluate(({ id, field }) => {
    const f = window.homesimEditor.workspace().getBlockById(id).getField(field);
    const r = f.getSvgRoot().getBoundingClientRect();
    return { x: r.left + r.width / 2, y: r.top + r.height / 2 };
  }, { id, field });
  let box = await fieldBox();
  for (let i = 0; i < 20; i++) {
    await page.waitForTimeout(50);
    const again = await fieldBox();
    if (again.x === box.x && again.y === box.y) break;
    box = again;
  }
  const menu = page.locator(".blocklyDropDownDiv .blocklyMenuItem");
  for (let attempt = 1; ; attempt++) {
    if (attempt > 1) box = await fieldBox();
    await page.mouse.click(box.x, box.y);
    try {
      await menu.first().waitFor({ state: "attached", timeout: 3000 });
      break;
    } catch (e) {
      if (attempt === 3) {
        const dbg = await page.evaluate(({ x, y }) => {
          const el = document.elementFromPoint(x, y);
          const ws = window.homesimEditor.workspace();
          return { at: `${el?.tagName}.${el?.getAttribute("class")}`,
            flyout: ws.getToolbox().getFlyout().isVisible(), dragging: ws.isDragging(),
            selected: window.homesimEditor.Blockly.getSelected()?.type };
        }, box);
        throw new Error(`the ${field} dropdown did not open: ${JSON.stringify(dbg)}`);
      }
    }
  }
  const item = menu.filter({ hasText: label }).first();
  await item.scrollIntoViewIfNeeded();
  await item.click();
  const value = await page.evaluate(({ id, field }) =>
    window.homesimEditor.workspace().getBlockById(id).getFieldValue(field), { id, field });
  check(label.includes(` ${value} `), `dropdown ${field} is ${value}, not ${label}`);
}

/** The open bubble showing `text` (wrapped lines joined), and whether it lies inside the
 * block pane; asked again for up to 2 s, as the editor places a bubble after it opens. */
async function bubbleInPane(page, text) {
  let seen = null;
  for (let i = 0; i < 20 && !seen?.inside; i++) {
    if (i) await page.waitForTimeout(100);
    seen = await bubbleNow(page, text);
  }
  return seen;
}

async function bubbleNow(page, text) {
  return page.evaluate((text) => {
    const squash = (t) => t.replace(/\s+/g, "");
    const pane = document.querySelector("#blockly").getBoundingClientRect();
    const bubble = [...document.querySelectorAll(".blocklyBubble")]
      .find((b) => squash(b.textContent).includes(squash(text)));
    if (!bubble) return null;
    const r = bubble.getBoundingClientRect();
    return { inside: r.left >= pane.left && r.right <= pane.right && r.top >= pane.top
      && r.bottom <= pane.bottom, bubble: [r.left, r.top, r.right, r.bottom].map(Math.round),
      pane: [pane.left, pane.top, pane.right, pane.bottom].map(Math.round) };
  }, text);
}

async function save(page) {
  const [download] = await Promise.all([page.waitForEvent("download"),
    page.locator("#save").click()]);
  return { name: download.suggestedFilename(), text: await readFile(await download.path(), "utf8") };
}

async function runAndWait(page) {
  await page.locator("#run").click();
  await page.waitForFunction(() => /executable|✗/.test(document.querySelector("#status").textContent)
    && document.querySelectorAll("#results li").length > 0);
}

async function main() {
  const started = Date.now();
  const browser = await chromium.launch({
    executablePath: opts.chromium,
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
  const errors = [];
  try {
    const context = await browser.newContext({ viewport: { width: 1400, height: 820 },
      acceptDownloads: true });
    const page = await context.newPage();
    page.on("pageerror", (e) => errors.push(`page error: ${e.message}`));
    // API answers 4xx on purpose (a bad line); any other failed load is a bug.
    page.on("console", (m) => {
      if (m.type() === "error" && !m.text().startsWith("Failed to load resource")) {
        errors.push(`console: ${m.text()}`);
      }
    });
    page.on("response", (r) => {
      if (r.status() >= 400 && !new URL(r.url()).pathname.startsWith("/api/")) {
        errors.push(`${r.status()} for ${r.url()}`);
      }
    });
    page.setDefaultTimeout(15000);

    // 1. Open the page.
    step = "1. Open the page";
    await page.goto(opts.url);
    await page.waitForSelector("body[data-ready=true]");
    const categories = await page.locator(".blocklyToolboxCategoryLabel").allTextContents();
    check(categories.length === 10, `expected 9 categories + free text, got ${categories}`);

    // 2. Build "watch TV" from blocks, run it, every step passes.
    step = "2. Build watch TV from blocks and run it";
    for (const [category, type, objects] of WATCH_TV) {
      const id = await dragBlock(page, category, type);
      for (const [slot, label] of objects.entries()) await pickOption(page, id, `OBJ${slot}`, label);
    }
    await page.locator("#title").fill("Watch TV");
    await page.locator("#description").fill(
      "Walk to the TV and switch it on, then sit on the sofa and watch TV.");
    await page.waitForFunction((t) => document.querySelector("#text").value === t, EXPECTED_TEXT)
      .catch(async () => {
        throw new Error(`text view is ${JSON.stringify(await page.locator("#text").inputValue())}`);
      });
    await runAndWait(page);
    const ok = await page.locator("#results li.ok").count();
    const failed = await page.locator("#results li.fail").count();
    check(ok === 5 && failed === 0, `watch TV: ${ok} steps passed, ${failed} failed`);
    check((await page.locator("#status").textContent()).includes("all 5 steps ran"),
      "status does not say the program is executable");

    // 3. Add a failing step: its reason shows on its block.
    step = "3. Add a failing step";
    const grab = await dragBlock(page, "Hands", "GRAB");
    await pickOption(page, grab, "OBJ0", TV);
    await runAndWait(page);
    const failRow = page.locator("#results li.fail");
    check(await failRow.count() === 1, "the failing step is not marked ✗");
    check((await failRow.textContent()).includes(GRAB_REASON), "the ✗ row lacks the reason");
    // The bubble opens once Blockly has rendered the block (asynchronously).
    await page.waitForFunction((id) => window.homesimEditor.workspace().getBlockById(id)
      .getIcon(window.homesimEditor.Blockly.icons.IconType.WARNING)?.bubbleIsVisible(), grab,
    { timeout: 3000 }).catch(() => {});
    const warning = await page.evaluate((id) => {
      const block = window.homesimEditor.workspace().getBlockById(id);
      const icon = block.getIcon(window.homesimEditor.Blockly.icons.IconType.WARNING);
      return icon ? { text: icon.getText(), open: icon.bubbleIsVisible() } : null;
    }, grab);
    // The reason, then what to do about its kind (affordance: another object).
    check(warning && warning.text.replace(/\s+/g, " ") === `${GRAB_REASON} (${AFFORDANCE_HINT})`
      && warning.open, `the Grab block's warning is ${JSON.stringify(warning)}`);
    check(await page.locator(`[data-id="${grab}"].hsFailed`).count() === 1,
      "the failing block is not outlined");
    await page.locator(".blocklyBubble", { hasText: GRAB_REASON }).first()
      .waitFor({ state: "visible" });
    if (opts.screenshot) await page.screenshot({ path: opts.screenshot });

    // 4. Save writes the ActivityPrograms file.
    step = "4. Save the program file";
    const saved = await save(page);
    check(saved.name === "Watch_TV.txt", `saved as ${saved.name}`);
    check(saved.text === `${EXPECTED_TEXT}[Grab] <tv> (1.410)\n`,
      `saved file is ${JSON.stringify(saved.text)}`);

    // 5. Load reads an ActivityPrograms file back into blocks (the demo program's file).
    step = "5. Load a program file";
    await page.locator("#clear").click();
    await page.locator("#load").setInputFiles(EXAMPLE);
    await page.waitForFunction(() => window.homesimEditor.workspace().getAllBlocks(false).length === 5);
    const loaded = await page.evaluate(() => window.homesimEditor.workspace().getAllBlocks(false)
      .map((b) => b.type));
    check(loaded.every((t) => t !== "hs_free_text"), `loaded blocks are ${loaded}`);
    check(await page.locator("#title").inputValue() === "Watch TV", "loading did not set the title");
    await runAndWait(page);
    check(await page.locator("#results li.ok").count() === 5, "the loaded program does not run");

    // 6. Pasting a program makes blocks; a bad line becomes free text with its error.
    step = "6. Paste a program";
    const pasted = "Pasted\nA pasted program.\n\n[Walk] <sofa> (1.352)\n[Wlak] <tv> (1.410)\n";
    await page.locator("#text").fill(pasted);
    await page.waitForFunction(() => window.homesimEditor.workspace().getAllBlocks(false).length === 2);
    const types = await page.evaluate(() => window.homesimEditor.workspace().getTopBlocks(true)[0]
      ? [window.homesimEditor.workspace().getTopBlocks(true)[0].type,
        window.homesimEditor.workspace().getTopBlocks(true)[0].getNextBlock()?.type] : []);
    check(types[0] === "hs_WALK" && types[1] === "hs_free_text", `pasted blocks are ${types}`);
    check(await page.locator("#title").inputValue() === "Pasted", "pasting did not set the title");
    await page.waitForFunction(() => document.querySelector("#status").textContent
      .includes("unknown action 'Wlak' (did you mean Walk?)"));

    // 7. Another home: refs that are not its nodes become free text; no line is lost.
    step = "7. Another home";
    await page.locator("#home").selectOption("scene2_trimmed");
    await page.waitForFunction(() => window.homesimEditor.workspace().getAllBlocks(false)
      .every((b) => b.type === "hs_free_text"));
    check((await page.locator("#text").inputValue()).includes("[Walk] <sofa> (1.352)"),
      "switching homes lost a line");

    // 8. Key frames: pictures when homesim.render is installed, else a clear message.
    step = "8. Key frames";
    await page.locator("#home").selectOption("scene1");
    await page.locator("#text").fill(EXPECTED_TEXT);
    await page.waitForFunction(() => window.homesimEditor.workspace().getAllBlocks(false).length === 5);
    await page.locator("#render").click();
    await page.waitForFunction(() => /key frames$|rendering is not available/.test(
      document.querySelector("#status").textContent), null, { timeout: 120000 });
    const frames = await page.locator("#frames img").count();
    const status = await page.locator("#status").textContent();
    check(frames === 5 || status.includes("rendering is not available"),
      `key frames: ${frames} images, status ${status}`);
    // 8b. Play video: the whole program rendered on the server, played in the strip.
    await page.locator("#video").click();
    await page.waitForFunction(() => /^(✓|✗) video/.test(
      document.querySelector("#video-status").textContent), null, { timeout: 150000 });
    const videoStatus = await page.locator("#video-status").textContent();
    let video = { duration: 0, width: 0 };
    if (videoStatus.startsWith("✓")) {
      await page.waitForFunction(() => document.querySelector("#video-player").readyState >= 2,
        null, { timeout: 20000 });
      video = await page.evaluate(() => {
        const v = document.querySelector("#video-player");
        return { duration: v.duration, width: v.videoWidth };
      });
    }
    check((video.duration > 3 && video.width === 320)
      || videoStatus.includes("rendering is not available"),
    `video: ${videoStatus} ${JSON.stringify(video)}`);
    if (opts.shots) await page.screenshot({ path: `${opts.shots}/video.png` });

    // 9. A check that fails drops the results of the earlier program; the error names the
    step = "9. A failing check drops earlier results";
    // line of the text as the user wrote it, and its bubble fits in the pane.
    await runAndWait(page);
    check(await page.locator("#results li.ok").count() === 5, "watch TV did not run again");
    await page.locator("#text").fill(TYPO);
    await page.waitForFunction(() => document.querySelector("#status").textContent.startsWith("✗"));
    const typoStatus = await page.locator("#status").textContent();
    check(typoStatus === `✗ ${TYPO_MESSAGE}`, `status for a typo on line 4: ${typoStatus}`);
    const stale = await page.locator("#results li").count() + await page.locator("#frames img").count();
    check(stale === 0, `${stale} results of the earlier program stay under the error`);
    await page.locator(".blocklyBubble").first().waitFor({ state: "visible" });
    const typoBubble = await bubbleInPane(page, TYPO_MESSAGE.slice(TYPO_MESSAGE.indexOf(":")));
    check(typoBubble?.inside, `the typo's bubble is not inside the pane: ${JSON.stringify(typoBubble)}`);
    const grabBubble = await (async () => {
      await page.locator("#text").fill(`${EXPECTED_TEXT}[Grab] <tv> (1.410)\n`);
      await page.waitForFunction(() => window.homesimEditor.workspace().getAllBlocks(false).length === 6);
      await runAndWait(page);
      await page.locator(".blocklyBubble", { hasText: GRAB_REASON }).first().waitFor({ state: "visible" });
      return bubbleInPane(page, GRAB_REASON);
    })();
    check(grabBubble?.inside, `the Grab bubble is not inside the pane: ${JSON.stringify(grabBubble)}`);
    // A narrow window: no room beside the block, so the bubble goes under it.
    await page.setViewportSize({ width: 900, height: 820 });
    await runAndWait(page);
    await page.locator(".blocklyBubble", { hasText: GRAB_REASON }).first().waitFor({ state: "visible" });
    const narrowBubble = await bubbleInPane(page, GRAB_REASON);
    check(narrowBubble?.inside,
      `in a 900 px window the Grab bubble is not inside the pane: ${JSON.stringify(narrowBubble)}`);
    await page.setViewportSize({ width: 1400, height: 820 });

    // 10. A README-style program (objects by class, no node ids) becomes action blocks with
    step = "10. A README-style program";
    // unbound objects ("any tv (1)"), keeps its refs as written, and runs (the server binds them).
    await page.locator("#text").fill(README);
    await page.waitForFunction(() => window.homesimEditor.workspace().getAllBlocks(false).length === 5);
    const readme = await page.evaluate(() => window.homesimEditor.workspace().getAllBlocks(true)
      .map((b) => `${b.type} ${b.getField("OBJ0")?.getText() ?? b.getFieldValue("TEXT")}`));
    check(JSON.stringify(readme) === JSON.stringify(["hs_WALK any tv (1)", "hs_SWITCHON any tv (1)",
      "hs_WALK any sofa (1)", "hs_SIT any sofa (1)", "hs_WATCH any tv (1)"]),
    `README blocks are ${readme}`);
    const readmeSaved = await save(page);
    check(readmeSaved.text === `Untitled\n\n\n${README}`,
      `the README program saves as ${JSON.stringify(readmeSaved.text)}`);
    await runAndWait(page);
    check(await page.locator("#results li.ok").count() === 5, "the README program does not run");
    if (opts.shots) await page.screenshot({ path: `${opts.shots}/readme.png` });
    // Picked nodes beside unbound objects are bound again by the server: the status says so.
    await page.locator("#text").fill("[Walk] <tv> (1)\n[Walk] <sofa> (1.352)\n");
    await page.waitForFunction(() => document.querySelector("#status").textContent
      .includes("picks every object anew"));

    // 11. Write: a program written for the title and description becomes blocks and runs
    step = "11. Write (the server's program writer; its model: 'homesim learn fit-writer')";
    // (the server's program writer; without the real programs fetched, a clear message).
    await page.locator("#clear").click();
    await page.locator("#title").fill("Watch TV");
    await page.locator("#description").fill("Turn on the TV and watch it from the sofa.");
    await page.locator("#write").click();
    // The server never fits the writer's model: it is there ('homesim learn fit-writer',
    // which make test runs first) and a write takes seconds once it is loaded, or the
    // answer says so. The first write loads it: over 60 s on a loaded two-core machine.
    await page.waitForFunction(() => /^✓ written|^✗ written|homesim data fetch|fit-writer|not available/
      .test(document.querySelector("#status").textContent), null, { timeout: 180000 });
    const writeStatus = await page.locator("#status").textContent();
    const writtenBlocks = await page.evaluate(() => window.homesimEditor.workspace()
      .getAllBlocks(false).map((b) => b.type));
    const writtenText = await page.locator("#text").inputValue();
    if (writeStatus.startsWith("✓ written")) {
      check(writtenText.startsWith("Watch TV\nTurn on the TV and watch it from the sofa.\n\n"),
        `the written program's text is ${JSON.stringify(writtenText)}`);
      check(writtenBlocks.includes("hs_SWITCHON") && !writtenBlocks.includes("hs_free_text"),
        `written blocks are ${writtenBlocks}`);
      check(await page.locator("#results li.ok").count() === writtenBlocks.length,
        "the written program's run is not shown step by step");
    } else {
      check(writeStatus.includes("homesim data fetch") || writeStatus.includes("fit-writer")
        || writeStatus.includes("not available"), `write: ${writeStatus}`);
    }
    if (opts.shots) await page.screenshot({ path: `${opts.shots}/write.png` });

    check(errors.length === 0, `browser errors: ${errors.join(" | ")}`);
    console.log(JSON.stringify({ ok: true, seconds: (Date.now() - started) / 1000,
      keyframes: frames, video }));
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(`e2e failed at step ${step}: ${e.message.split("\n")[0]}`);
  process.exit(1);
});
