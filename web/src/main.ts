// The editor page: a Blockly workspace (zelos renderer) kept in sync with a program text,
// checked and run by the homesim server.
import * as Blockly from "blockly/core";
import * as En from "blockly/msg/en";
import {
  ApiError, api, frameUrl, renderKeyFrames, renderVideo, videoUrl, type Execution,
  type FailureKind, type RenderJob,
} from "./api";
import { defineBlocks, toolbox } from "./blocks";
import { parseUnbound, setObjects, setUnbound } from "./objects";
import { itemsToState, parseText, workspaceToText, type Generated } from "./program";
import "./style.css";

Blockly.setLocale(En as unknown as { [key: string]: string });

const $ = <T extends HTMLElement>(id: string): T => document.getElementById(id) as T;
const homeSelect = $<HTMLSelectElement>("home");
const titleInput = $<HTMLInputElement>("title");
const descriptionInput = $<HTMLInputElement>("description");
const textArea = $<HTMLTextAreaElement>("text");
const statusLine = $<HTMLParagraphElement>("status");
const resultList = $<HTMLOListElement>("results");
const frameBox = $<HTMLDivElement>("frames");
const player = $<HTMLDivElement>("player");
const videoElement = $<HTMLVideoElement>("video-player");
const videoProgress = $<HTMLProgressElement>("video-progress");
const videoStatus = $<HTMLParagraphElement>("video-status");
const VIDEO_FPS = 12; // frames per second of the program's video
const BUBBLE_CHARS = 44; // warning bubbles wrap at this width, so they fit beside a block

let ws: Blockly.WorkspaceSvg;
let generated: Generated = { text: "", blockAtLine: new Map() };
// Block id -> its line in the text the user sees, which may differ from the generated text
// the server checks (a pasted text without a description line, blank lines, comments).
let shownLine = new Map<string, number>();
let applyingText = false;
let validateTimer: number | undefined;
let textTimer: number | undefined;
let requestEpoch = 0; // a check's answer is dropped once a newer check or run was asked for
let videoEpoch = 0; // a video job's updates are dropped once a newer one was asked for

function setStatus(message: string, kind: "ok" | "error" | "info" = "info"): void {
  statusLine.textContent = message;
  statusLine.className = kind;
}

function blockAtLine(line: number | null): Blockly.BlockSvg | null {
  const id = line === null ? undefined : generated.blockAtLine.get(line);
  return id ? ws.getBlockById(id) : null;
}

/** The line of the text area that holds the step the server numbers `line`. */
function lineShown(line: number): number {
  const id = generated.blockAtLine.get(line);
  return (id && shownLine.get(id)) || line;
}

/** `message` with the server's "line N" (of the text it was sent) renumbered as shown. */
function asShown(message: string, line: number | null): string {
  return line === null ? message : message.replace(/^line \d+:/, `line ${lineShown(line)}:`);
}

/** Whether `text` has both objects picked from the home and unbound ones: the server
 * then binds them all again (a partly grounded program counts as ungrounded). */
function mixesBoundAndUnbound(text: string): boolean {
  const refs = [...text.matchAll(/<[^<>]*>\s*\(\s*\d+\s*(\.\s*\d+)?\s*\)/g)];
  const bound = refs.filter((m) => m[1] !== undefined).length;
  return bound > 0 && bound < refs.length;
}

function clearResults(): void {
  resultList.replaceChildren();
  frameBox.replaceChildren();
  clearVideo();
}

/** Hide the video of an earlier program (and forget a video job still under way). */
function clearVideo(): void {
  videoEpoch++;
  player.hidden = true;
  videoElement.pause();
  videoElement.removeAttribute("src");
  videoElement.load();
}

function setVideoStatus(message: string, kind: "ok" | "error" | "info" = "info"): void {
  videoStatus.textContent = message;
  videoStatus.className = kind;
}

function showVideoProgress(job: RenderJob): void {
  if (job.status === "queued") {
    videoProgress.removeAttribute("value"); // indeterminate
    setVideoStatus("video: waiting for a render worker…");
  } else if (job.total > 0) {
    videoProgress.max = job.total;
    videoProgress.value = job.ready;
    setVideoStatus(`rendering video… ${job.ready} of ${job.total} frames`);
  } else {
    videoProgress.removeAttribute("value");
    setVideoStatus("rendering video… (animating the program)");
  }
}

/** Render the whole program as a video (a job on the server) and play it in the strip. */
async function playVideo(): Promise<void> {
  clearVideo();
  const epoch = videoEpoch;
  if (generated.blockAtLine.size === 0) {
    setStatus("Nothing to render: the program has no steps.", "error");
    return;
  }
  player.hidden = false;
  videoElement.hidden = true;
  videoProgress.hidden = false;
  showVideoProgress({ status: "queued" } as RenderJob);
  try {
    const job = await renderVideo(generated.text, homeSelect.value, VIDEO_FPS, (update) => {
      if (epoch === videoEpoch) showVideoProgress(update);
    });
    if (epoch !== videoEpoch) return;
    videoProgress.hidden = true;
    videoElement.src = videoUrl(job.id);
    videoElement.hidden = false;
    const seconds = job.total / (job.fps ?? VIDEO_FPS);
    setVideoStatus(`✓ video: ${job.total} frames, ${seconds.toFixed(1)} s`, "ok");
    await videoElement.play().catch(() => undefined); // if autoplay is refused: controls
  } catch (e) {
    if (epoch !== videoEpoch) return;
    videoProgress.hidden = true;
    const message = e instanceof ApiError ? asShown(e.message, e.line)
      : `cannot reach the server (${String(e)})`;
    setVideoStatus(`✗ video: ${message}`, "error");
    if (e instanceof ApiError) markBlock(e.line, message);
  }
}

function clearMarks(): void {
  ws.highlightBlock(null);
  for (const block of ws.getAllBlocks(false)) {
    block.setWarningText(null);
    block.removeClass("hsFailed");
  }
}

/** Put `reason` on the block of `line` and open its bubble, so the reason is in view. */
function markBlock(line: number | null, reason: string): void {
  const block = blockAtLine(line);
  if (!block) return;
  block.setWarningText(Blockly.utils.string.wrap(reason, BUBBLE_CHARS));
  block.addClass("hsFailed");
  ws.highlightBlock(block.id, true);
  const icon = block.getIcon(Blockly.icons.IconType.WARNING);
  void icon?.setBubbleVisible(true).then(() => {
    const bubble = icon.getBubble() as Blockly.bubbles.Bubble | null;
    if (bubble) placeBubble(block, bubble);
  });
}

/** Beside the block when the pane has room (so it hides no other step), else under it;
 * then scroll the workspace so the whole bubble is in view. */
function placeBubble(block: Blockly.BlockSvg, bubble: Blockly.bubbles.Bubble): void {
  const box = (bubble.getSvgRoot() as SVGGraphicsElement).getBBox(); // workspace units
  const view = ws.getMetricsManager().getViewMetrics(true);
  const at = block.getRelativeToSurfaceXY();
  const fitsBeside = at.x + block.width + 8 + box.width <= view.left + view.width - 16;
  bubble.setPositionRelativeToAnchor(0, 0); // offsets count from the anchor: find it
  const anchor = bubble.getRelativeToSurfaceXY();
  const left = fitsBeside ? at.x + block.width + 8 : at.x;
  const top = fitsBeside ? at.y : at.y + block.height + 4;
  bubble.setPositionRelativeToAnchor(left - anchor.x, top - anchor.y);
  const placed = bubble.getRelativeToSurfaceXY();
  ws.scrollBoundsIntoView(new Blockly.utils.Rect(placed.y, placed.y + box.height, placed.x,
    placed.x + box.width), 16);
}

function regenerate(): void {
  generated = workspaceToText(ws, titleInput.value, descriptionInput.value);
  if (!applyingText && document.activeElement !== textArea) {
    textArea.value = generated.text;
    shownLine = new Map([...generated.blockAtLine].map(([line, id]) => [id, line]));
  }
  scheduleValidate();
}

function applyText(text: string): void {
  const parsed = parseText(text);
  titleInput.value = parsed.title;
  descriptionInput.value = parsed.description;
  setUnbound(parsed.items.flatMap((item) =>
    item.kind === "action" ? item.values.filter((v) => parseUnbound(v)) : []));
  applyingText = true;
  Blockly.Events.disable();
  try {
    ws.clear();
    Blockly.serialization.workspaces.load(itemsToState(parsed.items), ws);
  } finally {
    Blockly.Events.enable();
    applyingText = false;
  }
  // One stack, one block per item, in order: each block remembers its line in `text`.
  shownLine = new Map();
  let block: Blockly.Block | null = ws.getTopBlocks(true)[0] ?? null;
  for (const item of parsed.items) {
    if (!block) break;
    shownLine.set(block.id, item.line);
    block = block.getNextBlock();
  }
  generated = workspaceToText(ws, titleInput.value, descriptionInput.value);
  scheduleValidate();
}

function scheduleValidate(): void {
  window.clearTimeout(validateTimer);
  validateTimer = window.setTimeout(() => void validate(), 500);
}

async function validate(): Promise<void> {
  if (generated.blockAtLine.size === 0) {
    setStatus("Drag blocks from the categories, or paste a program into the text.");
    return;
  }
  const sent = generated.text;
  const epoch = ++requestEpoch;
  const stale = (): boolean => epoch !== requestEpoch || sent !== generated.text;
  try {
    const result = await api.validate(sent, homeSelect.value);
    if (stale()) return;
    clearMarks();
    for (const problem of result.problems) {
      markBlock(problem.line, asShown(problem.message, problem.line));
    }
    if (result.ok) {
      const note = mixesBoundAndUnbound(sent)
        ? " (it has \"any\" objects, so the server picks every object anew when it runs)" : "";
      setStatus(`✓ valid program, ${generated.blockAtLine.size} steps${note}`, "ok");
    } else {
      clearResults(); // they were for an earlier program
      const first = result.problems[0];
      setStatus(`✗ ${asShown(first.message, first.line)}`, "error");
    }
  } catch (e) {
    if (stale()) return;
    clearMarks();
    clearResults();
    showError(e);
  }
}

function showError(e: unknown): void {
  if (e instanceof ApiError) {
    const message = asShown(e.message, e.line);
    setStatus(`✗ ${message}`, "error");
    markBlock(e.line, message);
  } else {
    setStatus(`✗ cannot reach the server (${String(e)})`, "error");
  }
}

/** What to do about a failed step, by its kind (the server's words say why). */
const HINTS: Record<FailureKind, string> = {
  missing: "the home has no such object",
  unreachable: "the character must walk to it first",
  not_facing: "the character must turn to it first",
  enclosed: "open what it is inside first",
  not_held: "the character must hold it first",
  hands_full: "put something down first",
  posture: "the character must stand up (or sit) first",
  already: "it is so already; drop this step",
  affordance: "this object cannot do that; choose another",
  state: "it needs another state first",
};

function withHint(reason: string, kind: FailureKind | null): string {
  return kind ? `${reason} (${HINTS[kind]})` : reason;
}

function showRun(result: Execution): void {
  resultList.replaceChildren();
  const inserted = new Map((result.repair?.insertions ?? []).map((i) => [i.index, i.reason]));
  for (const step of result.steps) {
    const item = document.createElement("li");
    const added = inserted.get(step.index);
    item.className = (step.ok ? "step ok" : "step fail") + (added ? " inserted" : "");
    if (step.line !== null) item.dataset.line = String(step.line);
    if (step.kind) item.dataset.kind = step.kind;
    const mark = added ? "+" : step.ok ? "✓" : "✗";
    item.innerHTML = `<span class="mark">${mark}</span> <code></code>
      <div class="detail"></div>`;
    item.querySelector("code")!.textContent = step.step;
    const detail = step.ok ? step.summary : withHint(step.reason ?? "", step.kind);
    item.querySelector(".detail")!.textContent = added ? `inserted: ${added}; ${detail}` : detail;
    if (step.line !== null) {
      const line = step.line;
      item.addEventListener("click", () => blockAtLine(line)?.select());
    }
    resultList.append(item);
  }
  for (const step of result.not_run) {
    const item = document.createElement("li");
    item.className = "step notrun";
    item.innerHTML = `<span class="mark">·</span> <code></code> <div class="detail">not run</div>`;
    item.querySelector("code")!.textContent = step.step;
    resultList.append(item);
  }
  if (result.executable) {
    setStatus(`✓ ${result.message}`, "ok");
  } else {
    setStatus(`✗ ${result.message}`, "error");
    markBlock(result.failed_line, withHint(result.reason ?? "failed", result.kind));
  }
}

async function run(): Promise<void> {
  window.clearTimeout(validateTimer);
  requestEpoch++;
  clearMarks();
  clearResults();
  if (generated.blockAtLine.size === 0) {
    setStatus("Nothing to run: the program has no steps.", "error");
    return;
  }
  setStatus("running…");
  try {
    showRun(await api.execute(generated.text, homeSelect.value));
  } catch (e) {
    showError(e);
  }
}

/** Write a program for the title and description (the server's program writer, as
 * `homesim learn write`), show it as blocks and show its run. */
async function writeProgram(): Promise<void> {
  const description = descriptionInput.value.trim();
  if (!description) {
    setStatus("Type a description first: the program is written for it.", "error");
    return;
  }
  window.clearTimeout(validateTimer);
  requestEpoch++;
  clearMarks();
  clearResults();
  setStatus("writing a program for the description… (the first time takes a while)");
  try {
    const written = await api.write(description, titleInput.value.trim() || null,
      homeSelect.value);
    textArea.value = written.program;
    applyText(written.program);
    showRun(written.run);
    const guessed = written.title_given ? "" : ` (title guessed: ${written.title})`;
    const verdict = written.executable ? "✓ written and executable" : "✗ written, does not run";
    setStatus(`${verdict}: ${written.steps.length} steps${guessed}`,
      written.executable ? "ok" : "error");
  } catch (e) {
    showError(e);
  }
}

async function renderFrames(): Promise<void> {
  frameBox.replaceChildren();
  setStatus("rendering key frames…");
  try {
    const job = await renderKeyFrames(generated.text, homeSelect.value, (frame, progress) => {
      const figure = document.createElement("figure");
      const image = document.createElement("img");
      image.src = frameUrl(progress.id, frame.index);
      image.alt = `after step ${frame.index + 1}`;
      const caption = document.createElement("figcaption");
      caption.textContent = `after step ${frame.index + 1}`;
      figure.append(image, caption);
      frameBox.append(figure);
      setStatus(`rendering key frames… ${frame.index + 1} of ${progress.total}`);
    });
    setStatus(`✓ ${job.total} key frames`, "ok");
  } catch (e) {
    showError(e);
  }
}

function save(): void {
  const name = (titleInput.value.trim() || "program").replace(/[^\w-]+/g, "_");
  const link = document.createElement("a");
  link.href = URL.createObjectURL(new Blob([generated.text], { type: "text/plain" }));
  link.download = `${name}.txt`;
  link.click();
  URL.revokeObjectURL(link.href);
}

async function loadHome(name: string): Promise<void> {
  const { objects } = await api.objects(name);
  setObjects(objects);
  ws.getToolbox()?.refreshSelection();
  // Rebuild from the text: refs that are not nodes of this home become free text.
  applyText(textArea.value);
}

async function start(): Promise<void> {
  const [homes, catalog] = await Promise.all([api.homes(), api.actions()]);
  defineBlocks(catalog.categories);
  ws = Blockly.inject($("blockly"), {
    renderer: "zelos",
    toolbox: toolbox(catalog.categories),
    media: "media/",
    trashcan: true,
    move: { scrollbars: true, drag: true, wheel: true },
    zoom: { controls: true, startScale: 0.75 },
  });
  for (const home of homes.homes) homeSelect.add(new Option(home.name, home.name));
  homeSelect.value = new URLSearchParams(location.search).get("home") ?? homes.default;
  await loadHome(homeSelect.value);
  ws.addChangeListener((e) => {
    if (!e.isUiEvent && !applyingText) regenerate();
  });
  homeSelect.addEventListener("change", () => void loadHome(homeSelect.value).catch(showError));
  for (const input of [titleInput, descriptionInput]) input.addEventListener("input", regenerate);
  textArea.addEventListener("input", () => {
    window.clearTimeout(textTimer);
    textTimer = window.setTimeout(() => applyText(textArea.value), 400);
  });
  $("run").addEventListener("click", () => void run());
  $("write").addEventListener("click", () => void writeProgram());
  $("check").addEventListener("click", () => void validate());
  $("render").addEventListener("click", () => void renderFrames());
  $("video").addEventListener("click", () => void playVideo());
  videoElement.addEventListener("error", () => {
    if (!videoElement.getAttribute("src")) return;
    setVideoStatus("✗ video: this browser cannot play it (H.264 MP4); download it from "
      + new URL(videoElement.src, location.href).pathname, "error");
  });
  $("save").addEventListener("click", save);
  $("clear").addEventListener("click", () => { textArea.value = ""; applyText(""); });
  $<HTMLInputElement>("load").addEventListener("change", async (event) => {
    const input = event.target as HTMLInputElement;
    const file = input.files?.[0];
    if (!file) return;
    textArea.value = await file.text();
    applyText(textArea.value);
    input.value = "";
  });
  setStatus("Drag blocks from the categories, or paste a program into the text.");
  document.body.dataset.ready = "true";
}

declare global {
  interface Window { homesimEditor: { Blockly: typeof Blockly; workspace: () => Blockly.WorkspaceSvg } }
}
window.homesimEditor = { Blockly, workspace: () => ws };

start().catch((e) => {
  setStatus(`✗ the editor could not start: ${e instanceof Error ? e.message : String(e)}`,
    "error");
});
