// Blocks <-> program text (ActivityPrograms format: title, description, blank line, steps).
// The server's parser is the authority; this side only decides which lines become action
// blocks (a catalog action whose objects are nodes of the chosen home, of the class the
// text names, or unbound objects like `<tv> (1)`) and keeps every other line as a
// free-text block, so nothing pasted is lost.
import * as Blockly from "blockly/core";
import { FREE_TEXT, TEXT_FIELD, actionOf, blockType, lookupAction, objectField } from "./blocks";
import { objectById, parseUnbound, unboundValue } from "./objects";

export interface Generated {
  text: string;
  blockAtLine: Map<number, string>; // 1-based line number -> id of the block it came from
}

export const HEADER_LINES = 3; // title, description, blank line

/** The unbound objects the blocks use, by class: their instance numbers. */
function unboundInstances(blocks: Blockly.Block[]): Map<string, Set<number>> {
  const used = new Map<string, Set<number>>();
  for (const block of blocks) {
    const action = actionOf(block.type);
    for (let slot = 0; slot < (action?.arity ?? 0); slot++) {
      const ref = parseUnbound(String(block.getFieldValue(objectField(slot))));
      if (ref) used.set(ref.name, (used.get(ref.name) ?? new Set()).add(ref.instance));
    }
  }
  return used;
}

/** The program text of the workspace: stacks top to bottom, each block one line. */
export function workspaceToText(ws: Blockly.Workspace, title: string,
  description: string): Generated {
  const lines = [title.trim() || "Untitled", description.trim(), ""];
  const blockAtLine = new Map<number, string>();
  const blocks = ws.getTopBlocks(true).flatMap((top) => {
    const chain: Blockly.Block[] = [];
    for (let b: Blockly.Block | null = top; b; b = b.getNextBlock()) chain.push(b);
    return chain;
  });
  // Nodes get instances counted per class in order of first use, skipping the numbers
  // of unbound objects of the class (`<tv> (1)` and `<tv> (2.410)` are two tvs).
  const taken = unboundInstances(blocks);
  const instances = new Map<string, Map<number, number>>(); // class -> node -> instance
  const ref = (value: string): string => {
    const unbound = parseUnbound(value);
    if (unbound) return `<${unbound.name}> (${unbound.instance})`;
    const nodeId = Number(value);
    const name = objectById(nodeId)?.class_name ?? "unknown";
    const seen = instances.get(name) ?? new Map<number, number>();
    instances.set(name, seen);
    if (!seen.has(nodeId)) {
      let next = seen.size + 1;
      const used = new Set([...(taken.get(name) ?? []), ...seen.values()]);
      while (used.has(next)) next++;
      seen.set(nodeId, next);
    }
    return `<${name}> (${seen.get(nodeId)}.${nodeId})`;
  };
  for (const block of blocks) {
    let line: string;
    if (block.type === FREE_TEXT) {
      line = String(block.getFieldValue(TEXT_FIELD) ?? "").trim();
      if (!line) continue;
    } else {
      const action = actionOf(block.type);
      if (!action) continue;
      const args = [];
      for (let slot = 0; slot < action.arity; slot++) {
        args.push(ref(String(block.getFieldValue(objectField(slot)))));
      }
      line = [`[${action.name}]`, ...args].join(" ");
    }
    lines.push(line);
    blockAtLine.set(lines.length, block.id);
  }
  return { text: lines.join("\n") + "\n", blockAtLine };
}

/** A step or comment line of a text, with its 1-based line number there. */
export type Item =
  | { kind: "action"; key: string; values: string[]; line: number }
  | { kind: "free"; text: string; line: number };

export interface Parsed { title: string; description: string; items: Item[] }

const ACTION_RE = /^\s*\[([^[\]]*)\]/;
const ARG_RE = /^\s*<([^<>]*)>\s*\(\s*(\d+)(?:\s*\.\s*(\d+))?\s*\)/;

const isStep = (line: string): boolean => line.trimStart().startsWith("[");
const isSkippable = (line: string): boolean => !line.trim() || line.trim().startsWith("#");
const normalizeName = (name: string): string =>
  name.trim().toLowerCase().split(/\s+/).filter(Boolean).join("_");

function parseLine(line: string, lineNo: number): Item {
  const free: Item = { kind: "free", text: line.trim(), line: lineNo };
  const m = ACTION_RE.exec(line);
  const action = m ? lookupAction(m[1]) : undefined;
  if (!m || !action) return free;
  let rest = line.slice(m[0].length);
  const values: string[] = [];
  for (let a = ARG_RE.exec(rest); a; a = ARG_RE.exec(rest)) {
    const name = normalizeName(a[1]);
    if (!name) return free;
    if (a[3] === undefined) {
      values.push(unboundValue(name, Number(a[2]))); // any object of the class
    } else {
      // A node must be one of this home, of the class the text names.
      const node = Number(a[3]);
      if (objectById(node)?.class_name !== name) return free;
      values.push(String(node));
    }
    rest = rest.slice(a[0].length);
  }
  if (rest.trim() || values.length !== action.arity) return free;
  return { kind: "action", key: action.key, values, line: lineNo };
}

/** Split a program text into title, description and one item per step or comment line. */
export function parseText(text: string): Parsed {
  const lines = text.split(/\r?\n/);
  const items: Item[] = [];
  let i = 0;
  for (; i < lines.length && isSkippable(lines[i]); i++) {
    if (lines[i].trim()) items.push({ kind: "free", text: lines[i].trim(), line: i + 1 });
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
    if (lines[i].trim()) items.push(parseLine(lines[i], i + 1));
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
      item.values.forEach((value, slot) => { fields[objectField(slot)] = value; });
    }
    chain = { type, fields, ...(chain ? { next: { block: chain } } : {}) };
  }
  const blocks = chain ? [{ ...chain, x: 24, y: 24 }] : [];
  return { blocks: { languageVersion: 0, blocks } };
}
