// The objects of the chosen home as dropdown options. A slot holds either a node of the
// home ("410": that tv) or an unbound program object ("tv:1": `<tv> (1)`, any tv, bound
// to a node when the program runs). Objects that suit the action (the properties its
// catalog row `needs`) come first; the order is only a convenience: the simulator decides
// what is allowed and says why not.
import type { Action, HomeObject } from "./api";

let current: HomeObject[] = [];
let byId = new Map<number, HomeObject>();
let classes: string[] = [];
let unbound: string[] = []; // unbound values of the loaded text that the home may lack

export function setObjects(objects: HomeObject[]): void {
  current = objects;
  byId = new Map(objects.map((o) => [o.id, o]));
  classes = [...new Set(objects.map((o) => o.class_name))].sort();
}

/** Let the dropdowns offer these unbound values too (`<coffee_maker> (2)` of a text). */
export function setUnbound(values: string[]): void {
  unbound = [...new Set(values)];
}

export function objectById(id: number): HomeObject | undefined {
  return byId.get(id);
}

export function objectLabel(o: HomeObject): string {
  return `${o.class_name} ${o.id} · ${o.room ?? "no room"}`;
}

export interface Unbound { name: string; instance: number }

export const unboundValue = (name: string, instance: number): string => `${name}:${instance}`;

/** The class and instance of an unbound slot value, or null for a node id. */
export function parseUnbound(value: string): Unbound | null {
  const m = /^([^:]+):(\d+)$/.exec(value);
  return m ? { name: m[1], instance: Number(m[2]) } : null;
}

function unboundLabel(value: string): string {
  const ref = parseUnbound(value)!;
  return `any ${ref.name} (${ref.instance})`;
}

export type Option = [string, string] | "separator";

/** Whether `o` has, for every requirement of the slot, one of its properties. */
function suits(o: HomeObject, needs: string[][]): boolean {
  return needs.every((oneOf) => oneOf.some((p) => o.properties.includes(p)));
}

export function optionsFor(action: Action, slot: number): Option[] {
  const needs = action.needs[slot] ?? [];
  const nodes = (list: HomeObject[]): Option[] =>
    list.map((o): [string, string] => [objectLabel(o), String(o.id)]);
  const anyOf = (values: string[]): Option[] =>
    values.map((v): [string, string] => [unboundLabel(v), v]);
  const good = needs.length ? current.filter((o) => suits(o, needs)) : [];
  const rest = good.length ? current.filter((o) => !suits(o, needs)) : current;
  const goodClasses = new Set(good.map((o) => o.class_name));
  const firstOf = (c: string[]): string[] => c.map((name) => unboundValue(name, 1));
  const unboundValues = [...new Set([
    ...unbound,
    ...firstOf(classes.filter((c) => goodClasses.has(c))),
    ...firstOf(classes.filter((c) => !goodClasses.has(c))),
  ])];
  const options: Option[] = [];
  for (const group of [nodes(good), nodes(rest), anyOf(unboundValues)]) {
    if (group.length === 0) continue;
    if (options.length) options.push("separator");
    options.push(...group);
  }
  return options.length ? options : [["(no home loaded)", "none"]];
}
