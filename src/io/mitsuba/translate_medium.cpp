// Mitsuba's participating media: <medium type="homogeneous"> or "heterogeneous" (top level with
// an id, nested in a shape as "interior" or "exterior", or in the sensor), its <phase> and its
// <volume>s (constvolume, gridvolume), into our "media" block (the medium family's table checks
// the values).
#include "core/media/registry.h"
#include "io/mitsuba/translator.h"

namespace caustica::mitsuba_translation {

// A <volume> inside a medium: a homogeneous medium takes a constvolume's value; with `placed`
// (a heterogeneous medium's sigma_t, or its albedo grid) a volume block placed as Mitsuba places it (the unit cube under to_world, or the grid
// file's box with use_grid_bbox; voxel values at the cells' centres, clamped at the edges).
// A coefficient: a number, or a colour as given (the reader refuses a negative one, or an
// albedo above 1, instead of clamping it).
json Translator::coefficient(const XmlProperty& q) {
  if (q.kind == XmlProperty::Float || q.kind == XmlProperty::Integer) return q.number;
  return color_json(q, SpectrumUse::Unbounded);
}

json Translator::volume(const XmlObject& k, const std::string& p, bool placed) {
  Props vp(k);
  if (k.type == "constvolume") {
    const XmlProperty* v = vp.get("value");
    if (!v) throw InputError(k.where + ": a constvolume needs a value");
    note(p, v->where);
    json out = coefficient(*v);
    const XmlProperty* t = vp.get("to_world");
    if (placed) {
      out = {{"type", "constvolume"}, {"value", out}, {"to_world", rows(t ? transform(*t) : glm::dmat4(1.0))}};
      note(p + "/value", v->where);
    }
    refuse_unused(k, vp);
    return out;
  }
  if (k.type != "gridvolume" || !placed) {
    unsupported(k, "volume", placed ? std::set<std::string>{"constvolume", "gridvolume"} : std::set<std::string>{"constvolume"},
                "the medium is left out");
    return nullptr;
  }
  json out = {{"type", "gridvolume"}, {"voxels", "centres"}, {"box", "unit"}};
  note(p, k.where);
  const XmlProperty* f = vp.get("filename");
  if (!f) throw InputError(k.where + ": a gridvolume needs a filename");
  out["filename"] = resolve(k, *f);
  note(p + "/filename", f->where);
  if (const XmlProperty* t = vp.get("to_world")) {
    out["to_world"] = rows(transform(*t));
    note(p + "/to_world", t->where);
  }
  if (const XmlProperty* b = vp.get("use_grid_bbox")) out["box"] = boolean(*b) ? "file" : "unit";
  if (const XmlProperty* ft = vp.get("filter_type")) {
    const std::string s = string(*ft);
    if (s != "trilinear" && s != "nearest") throw InputError(ft->where + ": filter_type \"" + s + "\" (trilinear or nearest)");
    out["filter"] = s;
  }
  if (const XmlProperty* w = vp.get("wrap_mode")) {
    if (string(*w) != "clamp") unsupported_property(*w, "clamp in its place");
  }
  // raw: no colour transform of the stored values (ours stores RGB as is); accel: GPU textures.
  vp.ignore({"raw", "accel"});
  refuse_unused(k, vp);
  return out;
}

std::string Translator::medium(const XmlObject& o) {
  const auto it = media_.find(&o);
  if (it != media_.end()) return it->second;
  if (o.type != "homogeneous" && o.type != "heterogeneous") {
    unsupported(o, "medium", {"homogeneous", "heterogeneous"}, "ignored (vacuum in its place)");
    return "";
  }
  const bool hetero = o.type == "heterogeneous";
  std::string name = !o.id.empty() ? o.id : "medium" + std::to_string(++anonymous_);
  while (out_.doc["media"].contains(name)) name += "'";
  const std::string p = "/media/" + name;
  note(p, o.where);
  json m = {{"type", o.type}};
  Props props(o);
  for (const char* key : {"sigma_t", "albedo", "scale"}) {
    if (const XmlProperty* q = props.get(key)) {
      m[key] = key == std::string("scale") ? json(number(*q)) : coefficient(*q);
      note(p + "/" + key, q->where);
    }
  }
  // Mitsuba's heterogeneous medium is empty outside its sigma_t volume's box, a constant's too:
  // the unit cube under its to_world (identity when it has none, and for the default sigma_t 1).
  if (hetero && !(m.contains("sigma_t") && m["sigma_t"].is_object())) {
    m["sigma_t"] = {{"type", "constvolume"}, {"value", m.contains("sigma_t") ? m["sigma_t"] : json(1.0)},
                    {"to_world", rows(glm::dmat4(1.0))}};
  }
  // Mitsuba: emitters sampled from inside the medium (ours always are), spectral extinction.
  props.ignore({"sample_emitters", "has_spectral_extinction"});
  refuse_unused(o, props);
  for (const XmlChild& c : o.children) {
    const XmlObject& k = *c.object;
    if (k.tag == "phase") {
      if (k.type != "isotropic" && k.type != "hg") {
        unsupported(k, "phase", mitsuba_names(phase_plugins()), "isotropic in its place");
        continue;
      }
      Props pp(k);
      json phase = {{"type", k.type}};
      if (const XmlProperty* g = pp.get("g")) {
        phase["g"] = number(*g);
        note(p + "/phase/g", g->where);
      }
      refuse_unused(k, pp);
      m["phase"] = phase;
      note(p + "/phase", k.where);
    } else if (k.tag == "volume" && (c.name == "sigma_t" || c.name == "albedo")) {
      // Only the extinction's box bounds the medium: an albedo's constant needs none.
      const json v = volume(k, p + "/" + c.name, hetero && (c.name == "sigma_t" || k.type != "constvolume"));
      if (v.is_null()) return "";
      m[c.name] = v;
    } else {
      bad_child(o, c);
    }
  }
  out_.doc["media"][name] = m;
  media_[&o] = name;
  return name;
}

}  // namespace caustica::mitsuba_translation
