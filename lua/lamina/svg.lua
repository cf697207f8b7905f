-- lamina.svg: a contact sheet of layers as SVG, the layout of
-- `lamina slice --svg`.
--
--   local svg = require "lamina.svg"
--   assert(svg.contact_sheet(layers, "out/part.svg", { title = "part" }))
--
-- svg.contact_sheet(layers, path [, opts]) -> true | nil, message
-- svg.contact_sheet(layers) -> the SVG text
--   One 200 px panel per layer, all at the scale of the largest layer, in
--   a square-ish grid; each layer's contours make one path with
--   fill-rule="evenodd", so holes show as holes. More than opts.max_panels
--   (100) layers: that many, evenly chosen, and the title says so.
--   opts.title heads the sheet (default "lamina").
local svg = {}

local PANEL, PAD, LABEL, TOP = 200, 10, 18, 34

local ENTITIES = { ["<"] = "&lt;", [">"] = "&gt;", ["&"] = "&amp;", ['"'] = "&quot;" }
local function escape(s)
  return (tostring(s):gsub('[<>&"]', ENTITIES))
end

function svg.contact_sheet(layers, path, opts)
  opts = opts or {}
  local n, most = #layers, opts.max_panels or 100
  local shown = {}
  for k = 1, math.min(n, most) do
    shown[k] = n <= most and k or 1 + math.floor((k - 1) * (n - 1) / (most - 1) + 0.5)
  end
  -- one scale for all panels: the extent of every layer shown
  local u0, v0, u1, v1 = math.huge, math.huge, -math.huge, -math.huge
  for _, i in ipairs(shown) do
    local a, b, c, d = layers[i]:bbox()
    if a then
      u0, v0, u1, v1 = math.min(u0, a), math.min(v0, b), math.max(u1, c), math.max(v1, d)
    end
  end
  local size = math.max(u1 - u0, v1 - v0)
  local scale = size > 0 and (PANEL - 2 * PAD) / size or 1

  local cols = math.max(1, math.ceil(math.sqrt(#shown)))
  local rows = math.max(1, math.ceil(#shown / cols))
  local width, height = PAD + cols * (PANEL + PAD), TOP + rows * (PANEL + LABEL + PAD)
  local title = escape(opts.title or "lamina")
  title = title .. (#shown < n and (" (%d of %d layers shown, evenly chosen)"):format(#shown, n)
                    or (" (%d layer%s)"):format(n, n == 1 and "" or "s"))
  local out = {
    '<?xml version="1.0" encoding="UTF-8"?>',
    ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d">')
      :format(width, height, width, height),
    '<rect width="100%" height="100%" fill="#ffffff"/>',
    ('<text x="%d" y="22" font-family="sans-serif" font-size="15" fill="#222">%s</text>')
      :format(PAD, title),
  }
  for k, i in ipairs(shown) do
    local layer = layers[i]
    local x = PAD + ((k - 1) % cols) * (PANEL + PAD)
    local y = TOP + ((k - 1) // cols) * (PANEL + LABEL + PAD)
    out[#out + 1] = ('<g transform="translate(%d %d)">'):format(x, y)
    out[#out + 1] = ('<rect width="%d" height="%d" fill="#ffffff" stroke="#bbbbbb"/>')
      :format(PANEL, PANEL)
    local d = {}
    for _, c in ipairs(layer:contours()) do
      for j, u, v in c:points() do
        local x, y = (u - u0) * scale, (v1 - v) * scale -- v grows downwards in SVG
        d[#d + 1] = ("%s%.2f %.2f"):format(j == 1 and "M" or "L", x, y)
      end
      d[#d + 1] = "Z"
    end
    if #d > 0 then
      out[#out + 1] = ('<path transform="translate(%d %d)" fill="#2f6db5" fill-rule="evenodd" '
        .. 'stroke="#1b3f6b" stroke-width="0.5" d="%s"/>'):format(PAD, PAD, table.concat(d, " "))
    end
    out[#out + 1] = ('<text x="2" y="%d" font-family="sans-serif" font-size="12" fill="#222">'
      .. 'layer %d  h=%.4g  (%d contour%s)</text>'):format(PANEL + 14, i, layer.z, #layer,
      #layer == 1 and "" or "s")
    out[#out + 1] = "</g>"
  end
  out[#out + 1] = "</svg>\n"
  local text = table.concat(out, "\n")
  if not path then return text end
  local f, err = io.open(path, "w")
  if not f then return nil, err end
  local ok, werr = f:write(text)
  local closed, cerr = f:close()
  if not ok or not closed then return nil, ("%s: %s"):format(path, werr or cerr) end
  return true
end

return svg
