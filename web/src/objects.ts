// The objects of the chosen home as dropdown options; objects that suit the action
// (a switch for SwitchOn, a seat for Sit) come first. The order is only a convenience:
// the simulator decides what is allowed and says why not.
import type { HomeObject } from "./api";

// Action key -> the property an object should have for each argument slot.
const SUITS: Record<string, (string | null)[]> = {
  SWITCHON: ["HAS_SWITCH"], SWITCHOFF: ["HAS_SWITCH"], PLUGIN: ["HAS_PLUG"],
  PLUGOUT: ["HAS_PLUG"], SIT: ["SITTABLE"], LIE: ["LIEABLE"], GRAB: ["GRABBABLE"],
  DROP: ["GRABBABLE"], RELEASE: ["GRABBABLE"], OPEN: ["CAN_OPEN"], CLOSE: ["CAN_OPEN"],
  PUTBACK: ["GRABBABLE", "SURFACES"], PUTIN: ["GRABBABLE", "CONTAINERS"],
  PUTOBJBACK: ["GRABBABLE"], POUR: ["POURABLE", "RECIPIENT"], READ: ["READABLE"],
  DRINK: ["DRINKABLE"], EAT: ["EATABLE"], CUT: ["CUTTABLE"], PUTON: ["CLOTHES"],
  PUTOFF: ["CLOTHES"], WATCH: ["LOOKABLE"], LOOKAT: ["LOOKABLE"], TYPE: ["HAS_SWITCH"],
  MOVE: ["MOVABLE"], PUSH: ["MOVABLE"], PULL: ["MOVABLE"],
};

let current: HomeObject[] = [];
let byId = new Map<number, HomeObject>();

export function setObjects(objects: HomeObject[]): void {
  current = objects;
  byId = new Map(objects.map((o) => [o.id, o]));
}

export function objectById(id: number): HomeObject | undefined {
  return byId.get(id);
}

export function objectLabel(o: HomeObject): string {
  return `${o.class_name} ${o.id} · ${o.room ?? "no room"}`;
}

export type Option = [string, string] | "separator";

export function optionsFor(actionKey: string, slot: number): Option[] {
  if (current.length === 0) return [["(no home loaded)", "none"]];
  const wanted = SUITS[actionKey]?.[slot] ?? null;
  const all = current.map((o): [string, string] => [objectLabel(o), String(o.id)]);
  if (!wanted) return all;
  const suits = current.filter((o) => o.properties.includes(wanted));
  if (suits.length === 0) return all;
  const rest = current.filter((o) => !o.properties.includes(wanted));
  return [
    ...suits.map((o): [string, string] => [`${objectLabel(o)}`, String(o.id)]),
    "separator",
    ...rest.map((o): [string, string] => [objectLabel(o), String(o.id)]),
  ];
}
