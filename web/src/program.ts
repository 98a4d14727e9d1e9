// Blocks <-> program text (ActivityPrograms format: title, description, blank line, steps).
// The server's parser is the authority; this side only decides which lines become action
// blocks (a catalog action whose objects are nodes of the chosen home) and keeps every
// other line as a free-text block, so nothing pasted is lost.
import * as Blockly from "blockly/core";
import { FREE_TEXT, TEXT_FIELD, actionOf, blockType, objectField } from "./blocks";
import { objectById } from "./objects";

export interface Generated {
  text: string;
  blockAtLine: Map<number, string>; // 1-based line number -> id of the block it came from
}

export const HEADER_LINES = 3; // title, description, blank line

/** The program text of the workspace: stacks top to bottom, each block one line. */
export function workspaceToText(ws: Blockly.Workspace, title: string,
  description: string): Generated {
  const lines = [title.trim() || "Untitled", description.trim(), ""];
  const blockAtLine = new Map<number, string>();
  const instances = new Map<string, Map<number, number>>(); // class -> node -> instance
  const ref = (nodeId: number): string => {
    const name = objectById(nodeId)?.class_name ?? "unknown";
    const seen = instances.get(name) ?? new Map<number, number>();
    instances.set(name, seen);
    if (!seen.has(nodeId)) seen.set(nodeId, seen.size + 1);
    return `<${name}> (${seen.get(nodeId)}.${nodeId})`;
  };
  for (const top of ws.getTopBlocks(true)) {
    for (let block: Blockly.Block | null = top; block; block = block.getNextBlock()) {
      let line: string;
      if (block.type === FREE_TEXT) {
        line = String(block.getFieldValue(TEXT_FIELD) ?? "").trim();
        if (!line) continue;
      } else {
        const action = actionOf(block.type);
        if (!action) continue;
        const args = [];
        for (let slot = 0; slot < action.arity; slot++) {
          args.push(ref(Number(block.getFieldValue(objectField(slot)))));
        }
        line = [`[${action.name}]`, ...args].join(" ");
      }
      lines.push(line);
      blockAtLine.set(lines.length, block.id);
    }
  }
  return { text: lines.join("\n") + "\n", blockAtLine };
}

type Item =
  | { kind: "action"; key: string; nodes: number[] }
  | { kind: "free"; text: string };

export interface Parsed { title: string; description: string; items: Item[] }

const ALIASES: Record<string, string> = {
  PUT: "PUTBACK", LOOKAT_SHORT: "LOOKAT", LOOKAT_MEDIUM: "LOOKAT", LOOKAT_LONG: "LOOKAT",
};
const ACTION_RE = /^\s*\[([^[\]]*)\]/;
const ARG_RE = /^\s*<([^<>]*)>\s*\(\s*(\d+)(?:\s*\.\s*(\d+))?\s*\)/;

const isStep = (line: string): boolean => line.trimStart().startsWith("[");
const isSkippable = (line: string): boolean => !line.trim() || line.trim().startsWith("#");
const normalizeName = (name: string): string =>
  name.trim().toLowerCase().split(/\s+/).filter(Boolean).join("_");

function parseLine(line: string): Item {
  const free: Item = { kind: "free", text: line.trim() };
  const m = ACTION_RE.exec(line);
  if (!m) return free;
  let key = m[1].toUpperCase().replace(/[\s-]/g, "");
  key = ALIASES[key] ?? key;
  const action = actionOf(blockType(key));
  if (!action) return free;
  let rest = line.slice(m[0].length);
  const nodes: number[] = [];
  for (let a = ARG_RE.exec(rest); a; a = ARG_RE.exec(rest)) {
    const node = a[3] === undefined ? NaN : Number(a[3]);
    // Only refs grounded to a node of this home, of the class the text names, fit a block.
    if (objectById(node)?.class_name !== normalizeName(a[1])) return free;
    nodes.push(node);
    rest = rest.slice(a[0].length);
  }
  if (rest.trim() || nodes.length !== action.arity) return free;
  return { kind: "action", key, nodes };
}

/** Split a program text into title, description and one item per step or comment line. */
export function parseText(text: string): Parsed {
  const lines = text.split(/\r?\n/);
  const items: Item[] = [];
  let i = 0;
  for (; i < lines.length && isSkippable(lines[i]); i++) {
    if (lines[i].trim()) items.push({ kind: "free", text: lines[i].trim() });
  }
  let title = "";
  const description: string[] = [];
  if (i < lines.length && !isStep(lines[i])) {
    title = lines[i++].trim();
    for (; i < lines.length && lines[i].trim() && !isStep(lines[i]); i++) {
      description.push(lines[i].trim());
    }
  }
  for (; i < lines.length; i++) {
    if (lines[i].trim()) items.push(parseLine(lines[i]));
  }
  return { title, description: description.join(" "), items };
}

/** Workspace JSON with the items as one stack of blocks. */
export function itemsToState(items: Item[]): object {
  let chain: Record<string, unknown> | undefined;
  for (const item of [...items].reverse()) {
    const fields: Record<string, string> = {};
    let type = FREE_TEXT;
    if (item.kind === "free") {
      fields[TEXT_FIELD] = item.text;
    } else {
      type = blockType(item.key);
      item.nodes.forEach((node, slot) => { fields[objectField(slot)] = String(node); });
    }
    chain = { type, fields, ...(chain ? { next: { block: chain } } : {}) };
  }
  const blocks = chain ? [{ ...chain, x: 24, y: 24 }] : [];
  return { blocks: { languageVersion: 0, blocks } };
}
