// Mitsuba's participating media: <medium type="homogeneous"> (top level with an id, nested in a
// shape as "interior" or "exterior", or in the sensor), its <phase> and constant <volume>s, into
// our "media" block (the medium family's table checks the values).
#include "core/media/registry.h"
#include "io/mitsuba/translator.h"

namespace caustica::mitsuba_translation {

std::string Translator::medium(const XmlObject& o) {
  const auto it = media_.find(&o);
  if (it != media_.end()) return it->second;
  // (Mitsuba's heterogeneous media read gridvolumes in its own unit-cube convention: not yet.)
  if (o.type != "homogeneous") {
    unsupported(o, "medium", {"homogeneous"}, "ignored (vacuum in its place)");
    return "";
  }
  std::string name = !o.id.empty() ? o.id : "medium" + std::to_string(++anonymous_);
  while (out_.doc["media"].contains(name)) name += "'";
  const std::string p = "/media/" + name;
  note(p, o.where);
  json m = {{"type", "homogeneous"}};
  Props props(o);
  // A coefficient: a number, or a colour as given (the reader refuses a negative one, or an
  // albedo above 1, instead of clamping it).
  auto coefficient = [&](const XmlProperty& q) -> json {
    if (q.kind == XmlProperty::Float || q.kind == XmlProperty::Integer) return q.number;
    return color_json(q, SpectrumUse::Unbounded);
  };
  for (const char* key : {"sigma_t", "albedo", "scale"}) {
    if (const XmlProperty* q = props.get(key)) {
      m[key] = key == std::string("scale") ? json(number(*q)) : coefficient(*q);
      note(p + "/" + key, q->where);
    }
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
      // A constant volume is its value; a grid is not read yet.
      if (k.type != "constvolume") {
        unsupported(k, "volume", {"constvolume"}, "the medium is left out");
        return "";
      }
      Props vp(k);
      const XmlProperty* v = vp.get("value");
      if (!v) throw InputError(k.where + ": a constvolume needs a value");
      m[c.name] = coefficient(*v);
      note(p + "/" + c.name, v->where);
      refuse_unused(k, vp);
    } else {
      bad_child(o, c);
    }
  }
  out_.doc["media"][name] = m;
  media_[&o] = name;
  return name;
}

}  // namespace caustica::mitsuba_translation
