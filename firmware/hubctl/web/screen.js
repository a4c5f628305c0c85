// The operator screen (hubctl serve, docs/operator-screen.md). Every string from the server is
// put on the page with textContent, never as HTML: States come from anyone on the DDS domain.
"use strict";

function text(id, value) {
  document.getElementById(id).textContent = value;
}

function cell(row, value, className) {
  const td = document.createElement("td");
  td.textContent = value;
  if (className) td.className = className;
  row.appendChild(td);
}

function showOperator(op) {
  const who = document.getElementById("who");
  if (op.verified) {
    who.textContent = op.name;
    who.className = "verified";
  } else {
    who.textContent = op.topic === "" ? "no operator panel found" :
                      op.fresh ? "nobody verified" : "operator panel silent";
    who.className = "unverified";
  }
  let badge = "";
  // verified_for and t_plus are null when the State carried NaN (JSON has none).
  if (op.verified) badge = op.verified_for === null ? "verified" : "verified for " + Math.round(op.verified_for) + " s";
  if (op.last_badge === "rejected") badge += (badge ? " · " : "") + "last badge rejected: " + op.last_badge_reason;
  text("badge", badge);
  // Pressable either way: a press without a verified operator gets the server's refusal shown.
  document.getElementById("done").className = op.verified ? "" : "nobody";
  document.body.dataset.confirmSeq = String(op.confirm_seq);
}

function showInstruction(instruction) {
  if (instruction === null) {
    text("instruction-step", "");
    text("instruction", "no instruction yet");
  } else {
    text("instruction-step", instruction.step);
    text("instruction", instruction.text);
  }
}

function showStation(station) {
  const body = document.getElementById("station-rows");
  const rows = [];
  for (const s of station) {
    const row = document.createElement("tr");
    row.className = "fresh-" + s.fresh;
    cell(row, s.topic);
    cell(row, s.fresh);
    cell(row, s.lifecycle);
    cell(row, typeof s.t_plus === "number" ? s.t_plus.toFixed(1) : "-");
    cell(row, s.action === "" ? "-" : s.action);
    cell(row, s.errors.join(" · "), s.errors.length ? "errors" : "");
    rows.push(row);
  }
  body.replaceChildren(...rows);
}

function show(snapshot) {
  showOperator(snapshot.operator);
  showInstruction(snapshot.instruction);
  showStation(snapshot.station);
}

async function confirmDone() {
  const button = document.getElementById("done");
  button.disabled = true;
  try {
    // The header is what tells the server the press comes from this page (a page of another
    // origin cannot set it without a CORS preflight, which the server never grants).
    const response = await fetch("/confirm", {method: "POST", headers: {"X-Hubrt-Screen": "confirm"}});
    let message = response.statusText;
    try {
      message = (await response.json()).message;
    } catch (e) { /* not JSON: keep the status text */ }
    text("confirm-message", message);
    document.getElementById("confirm-message").className = response.ok ? "ok" : "refused";
  } catch (e) {
    text("confirm-message", "the screen's server does not answer");
    document.getElementById("confirm-message").className = "refused";
  }
  button.disabled = false;
}

function connect() {
  const events = new EventSource("/events");
  events.addEventListener("state", (event) => {
    text("link", "live");
    document.getElementById("link").className = "live";
    show(JSON.parse(event.data));
  });
  events.onerror = () => {
    text("link", "reconnecting…");
    document.getElementById("link").className = "silent";
  };
}

document.addEventListener("DOMContentLoaded", () => {
  document.getElementById("done").addEventListener("click", confirmDone);
  connect();
});
