#pragma once
/// @file
/// Parameter structs list their fields once, as member pointers, in a static `fields`:
///
///     template <class Fields>
///     static void fields(Fields& f) {
///       f("v0", &NavigationParams::v0, "cruise speed, m/s");  // a number, bool or NamedEnum
///       f.section("pid", &NavigationParams::heading_pid);     // a nested struct: pid.kp, ...
///       f.flatten(&ControllerConfig::params);                 // a struct whose keys sit here
///     }
///
/// The scenario reader and writer, the Python bindings and the key-table test all walk that one
/// listing, so a field added to a struct is read, written, bound and checked against the docs
/// without another list to keep. `visit_fields` hands one object's fields, as references, to an
/// archive with `operator()(key, field&, doc)` and `section(key, sub&)`.

#include <type_traits>

namespace floornav {

template <class Object, class Archive>
void visit_fields(Object& object, Archive& archive);

/// The listing's member pointers applied to one object (const or not).
template <class Object, class Archive>
class FieldRefs {
 public:
  using Owner = std::remove_const_t<Object>;

  FieldRefs(Object& object, Archive& archive) : object_(object), archive_(archive) {}

  template <class T>
  void operator()(const char* key, T Owner::*member, const char* doc) {
    archive_(key, object_.*member, doc);
  }
  template <class S>
  void section(const char* key, S Owner::*member) {
    archive_.section(key, object_.*member);
  }
  template <class S>
  void flatten(S Owner::*member) {
    visit_fields(object_.*member, archive_);
  }

 private:
  Object& object_;
  Archive& archive_;
};

template <class Object, class Archive>
void visit_fields(Object& object, Archive& archive) {
  FieldRefs<Object, Archive> refs(object, archive);
  std::remove_const_t<Object>::fields(refs);
}

}  // namespace floornav
