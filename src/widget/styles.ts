/**
 * Shadow-DOM styles of <pathwise-view>. The host defaults to 300×150 CSS
 * pixels, like <canvas> and <iframe>, so an element with no author CSS is
 * still visible; any page rule on the tag name overrides these, because
 * outer styles beat :host rules.
 */
export const ELEMENT_CSS = `
:host {
  display: inline-block;
  position: relative;
  width: 300px;
  height: 150px;
  overflow: hidden;
  contain: content;
  background: #111;
}
:host([hidden]) {
  display: none;
}
canvas {
  display: block;
  width: 100%;
  height: 100%;
}
canvas:focus-visible {
  outline: 2px solid Highlight;
  outline-offset: -2px;
}
.visually-hidden {
  position: absolute;
  width: 1px;
  height: 1px;
  overflow: hidden;
  clip-path: inset(50%);
  white-space: nowrap;
}
[part='message'] {
  position: absolute;
  inset: 0;
  display: flex;
  align-items: center;
  justify-content: center;
  box-sizing: border-box;
  padding: 0.75em;
  overflow: auto;
  font: 13px/1.4 system-ui, sans-serif;
  text-align: center;
  color: #f5f5f5;
  background: #3a1d1d;
  overflow-wrap: anywhere;
}
[part='message'][hidden] {
  display: none;
}
[part='status'] {
  position: absolute;
  left: 0;
  bottom: 0;
  padding: 0.25em 0.5em;
  font: 12px/1.4 system-ui, sans-serif;
  color: #f5f5f5;
  background: rgba(0, 0, 0, 0.6);
}
[part='status'][hidden] {
  display: none;
}
`;
