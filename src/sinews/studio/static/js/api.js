// Talking to the studio server: JSON, binary packs, downloads and websockets, with
// one-line errors.

import { decodePack } from "./pack.js";

/** An error the server (or the page) explains in one line. */
export class StudioError extends Error {}

async function check(response) {
  if (response.ok) return response;
  let message = `${response.status} ${response.statusText}`;
  try {
    const body = await response.json();
    if (body && body.error) message = body.error;
  } catch {
    // not JSON: keep the status line
  }
  throw new StudioError(message);
}

async function send(url, init) {
  try {
    return await check(await fetch(url, init));
  } catch (error) {
    if (error instanceof StudioError) throw error;
    throw new StudioError(`cannot reach the studio server (${error.message})`);
  }
}

function jsonInit(body) {
  return {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
  };
}

export async function getJSON(url) {
  return (await send(url)).json();
}

export async function postJSON(url, body) {
  return (await send(url, jsonInit(body))).json();
}

/** GET (or POST a JSON body to) a pack URL; resolves to {header, arrays, response}. */
export async function getPack(url, body) {
  const response = await send(url, body === undefined ? undefined : jsonInit(body));
  return { ...decodePack(await response.arrayBuffer()), response };
}

/** POST a file's bytes as the request body. */
export async function postFile(url, file) {
  const init = {
    method: "POST",
    headers: { "X-Song-Name": encodeURIComponent(file.name) },
    body: file,
  };
  return (await send(url, init)).json();
}

/** Ask for a file to be made (POST) and hand it to the browser as a download; resolves to its name. */
export async function download(url) {
  const response = await send(url, { method: "POST" });
  const disposition = response.headers.get("Content-Disposition") || "";
  const name = (disposition.match(/filename="?([^";]+)"?/) || [])[1] || "sinews-export";
  const link = document.createElement("a");
  link.href = URL.createObjectURL(await response.blob());
  link.download = name;
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(link.href), 60_000);
  return name;
}

/** Body genes as a query string: ?stiffness=0.7&… */
export function geneQuery(genes) {
  const params = new URLSearchParams();
  for (const [name, value] of Object.entries(genes)) params.set(name, value.toFixed(3));
  const text = params.toString();
  return text ? `?${text}` : "";
}

/**
 * Open a websocket to ``path`` on this server (binary messages as ArrayBuffers).
 * @param {string} path e.g. "/api/live"
 * @param {{message: function(string|ArrayBuffer), close: function(CloseEvent)}} on handlers
 * @returns {Promise<WebSocket>} resolves once open
 */
export function openSocket(path, on) {
  return new Promise((resolve, reject) => {
    const socket = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}${path}`);
    socket.binaryType = "arraybuffer";
    socket.onopen = () => resolve(socket);
    socket.onerror = () => reject(new StudioError("the live link to the server failed"));
    socket.onclose = (event) => on.close(event);
    socket.onmessage = (event) => on.message(event.data);
  });
}
