// Whether some textures hold only finite values (texture_is_finite), scanned
// the first time it is asked and remembered: for a computation that can leave
// out terms of the form 0 * read, the same bits only when no read is NaN or
// infinite (the error records' references, verify/psi_ms_reference.hpp
// and atmosphere/sky_integrator.hpp), and that most often never needs to ask.
// Thread-safe.
#pragma once

#include <initializer_list>
#include <mutex>
#include <vector>

#include "core/texture.hpp"

namespace skybake {

class CachedFiniteCheck {
 public:
  // Null entries are skipped; the textures must outlive this object.
  CachedFiniteCheck(std::initializer_list<const Texture*> textures) : textures_(textures) {}

  bool operator()() const {
    std::call_once(once_, [this] {
      finite_ = true;
      for (const Texture* t : textures_)
        if (t && !texture_is_finite(*t)) finite_ = false;
    });
    return finite_;
  }

 private:
  std::vector<const Texture*> textures_;
  mutable std::once_flag once_;
  mutable bool finite_ = false;
};

}  // namespace skybake
